// Placeholder: the 'impact' command is not implemented yet.
#include <stdexcept>

#include "commands.hpp"

namespace fremond::cli {

void add_impact_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("impact", "(not implemented yet)");
  cmd->callback([] { throw std::runtime_error("'impact' is not implemented yet"); });
}

}  // namespace fremond::cli
