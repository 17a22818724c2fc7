#pragma once
// The subcommands of `fremond`; each lives in its own file and registers itself on the app.
#include <CLI/CLI.hpp>

namespace fremond::cli {

/// `fremond impact FILE|-` (docs/problem-file.md).
void add_impact_command(CLI::App& app);
/// `fremond simulate SCENE.json --out DIR` and `--preset paper-bar`.
void add_simulate_command(CLI::App& app);
/// `fremond curve`: the data of Figs. 8 and 9.
void add_curve_command(CLI::App& app);
/// `fremond atlas`: where each law creates energy over a scene's impact configurations.
void add_atlas_command(CLI::App& app);
/// `fremond predict DATA --law LAW`: a law beside measured impacts (docs/measurements.md).
void add_predict_command(CLI::App& app);
/// `fremond fit DATA --law NAMES`: law families fitted and ranked (docs/measurements.md).
void add_fit_command(CLI::App& app);

}  // namespace fremond::cli
