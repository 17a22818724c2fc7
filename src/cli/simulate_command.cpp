// Placeholder: the 'simulate' command is not implemented yet.
#include <stdexcept>

#include "commands.hpp"

namespace fremond::cli {

void add_simulate_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("simulate", "(not implemented yet)");
  cmd->callback([] { throw std::runtime_error("'simulate' is not implemented yet"); });
}

}  // namespace fremond::cli
