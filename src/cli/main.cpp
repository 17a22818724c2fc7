// fremond: impact laws of rigid bodies from the command line.
#include <cstdio>
#include <exception>

#include "cli/commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"fremond: impact laws of rigid bodies (Newton, Poisson, Coulomb, Frémond)"};
  app.require_subcommand(1);
  fremond::cli::add_impact_command(app);
  fremond::cli::add_simulate_command(app);
  fremond::cli::add_curve_command(app);
  fremond::cli::add_atlas_command(app);
  fremond::cli::add_predict_command(app);
  fremond::cli::add_fit_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::RuntimeError& e) {
    return e.get_exit_code();  // a command's own exit status (documented in its --help)
  } catch (const CLI::ParseError& e) {
    // Help prints and exits 0; every usage error (unknown option, missing or bad value) exits 1,
    // as the commands' help says, not with the parser's own codes.
    return app.exit(e) == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fremond: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
