// The table of lgi's subcommands (all_commands.hpp).
#include "experiments/commands/all_commands.hpp"

namespace lgi::experiments {

const std::vector<CommandFactory>& all_commands() {
  static const std::vector<CommandFactory> table = {
      add_simulate_subcommand,   add_schemes_subcommand,     add_scenes_subcommand,  add_work_precision_subcommand,
      add_long_time_subcommand,  add_singularity_subcommand, add_stress_subcommand,  add_sweep_subcommand,
      add_equilibria_subcommand, add_bifurcation_subcommand, add_poincare_subcommand, add_region_subcommand,
      add_chaos_map_subcommand,  add_actions_subcommand,     add_indicators_subcommand, add_quantum_subcommand,
      add_periodic_subcommand,  add_frequencies_subcommand,
  };
  return table;
}

}  // namespace lgi::experiments
