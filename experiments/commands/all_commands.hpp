#pragma once
// The subcommands of `lgi`, one factory per commands/<name>_command.cpp, in the
// order `lgi --help` lists them. main.cpp hands this table to the command line
// (cli/cli.hpp), so the cli layer calls nothing of this one.
#include <vector>

#include "experiments/cli/commands.hpp"

namespace lgi::experiments {

Subcommand add_simulate_subcommand(CLI::App& app, const CommandContext& context);
Subcommand add_schemes_subcommand(CLI::App& app, const CommandContext& context);
Subcommand add_scenes_subcommand(CLI::App& app, const CommandContext& context);
Subcommand add_work_precision_subcommand(CLI::App& app, const CommandContext& context);
Subcommand add_long_time_subcommand(CLI::App& app, const CommandContext& context);
Subcommand add_singularity_subcommand(CLI::App& app, const CommandContext& context);
Subcommand add_stress_subcommand(CLI::App& app, const CommandContext& context);
Subcommand add_sweep_subcommand(CLI::App& app, const CommandContext& context);
Subcommand add_equilibria_subcommand(CLI::App& app, const CommandContext& context);   // equilibria_command.cpp
Subcommand add_bifurcation_subcommand(CLI::App& app, const CommandContext& context);  // equilibria_command.cpp
Subcommand add_poincare_subcommand(CLI::App& app, const CommandContext& context);
Subcommand add_region_subcommand(CLI::App& app, const CommandContext& context);
Subcommand add_chaos_map_subcommand(CLI::App& app, const CommandContext& context);
Subcommand add_actions_subcommand(CLI::App& app, const CommandContext& context);
Subcommand add_indicators_subcommand(CLI::App& app, const CommandContext& context);
Subcommand add_quantum_subcommand(CLI::App& app, const CommandContext& context);
Subcommand add_periodic_subcommand(CLI::App& app, const CommandContext& context);
Subcommand add_frequencies_subcommand(CLI::App& app, const CommandContext& context);

/// Every subcommand, in `lgi --help` order.
const std::vector<CommandFactory>& all_commands();

}  // namespace lgi::experiments
