// Placeholder: the 'curve' command is not implemented yet.
#include <stdexcept>

#include "commands.hpp"

namespace fremond::cli {

void add_curve_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("curve", "(not implemented yet)");
  cmd->callback([] { throw std::runtime_error("'curve' is not implemented yet"); });
}

}  // namespace fremond::cli
