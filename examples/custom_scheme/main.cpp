// Registers RKMK3-Heun (rkmk3_heun.hpp) with lgi, runs it through the same
// driver as `lgi simulate` (an H5MD file), then runs lgi's verification kit
// on it: order on non-commuting problems, symmetry and conservation where
// claimed, zero allocations per step. Exit status 1 if a stated fact fails.
// usage: custom_scheme OUT.h5
#include <exception>
#include <iostream>

#include "experiments/analysis/allocation_counter.hpp"  // in exactly one file: counts allocations
#include "experiments/analysis/scheme_verification.hpp"
#include "experiments/cli/simulation.hpp"
#include "experiments/io/scene_reader.hpp"
#include "integrators/registry/register_scheme.hpp"
#include "rkmk3_heun.hpp"

namespace integrators = lgi::integrators;

namespace {

/// The run through lgi's simulate driver: the book's Dzhanibekov flip, written as `lgi simulate` writes it.
bool simulate(const integrators::SchemeInfo& scheme, const char* out) {
  const lgi::system::Scene scene =
      lgi::experiments::read_scene(std::string(LGI_SCENES_DIR) + "/dzhanibekov_book_axis2.toml");
  lgi::experiments::SimulationRequest request;
  request.dt = 1e-3;
  request.out = out;
  request.force = true;
  const integrators::RunConfig cfg = lgi::experiments::simulation_config(request, scene, scheme);
  const auto outcome = lgi::experiments::run_simulation(scene, scheme, cfg, request, nullptr, nullptr);
  if (!outcome.stats.ok) {
    std::cerr << "custom_scheme: " << outcome.failure_message << '\n';
    return false;
  }
  std::cout << scheme.name << " (order " << scheme.order << "; " << scheme.reference << "): " << outcome.stats.steps
            << " steps to t = " << outcome.stats.t_final << ", " << outcome.error_summary << "; wrote " << out << '\n';
  return true;
}

}  // namespace

int main(int argc, char** argv) try {
  if (argc != 2) {
    std::cerr << "usage: custom_scheme OUT.h5\n";
    return 2;
  }
  integrators::register_scheme<custom::Rkmk3Heun>({.name = "rkmk3-heun", .family = "RKMK"});
  const integrators::SchemeInfo& scheme = *integrators::find_scheme("rkmk3-heun");

  if (!simulate(scheme, argv[1])) return 1;

  // lgi's verification kit.
  namespace verification = lgi::experiments::verification;
  verification::Options options;
  options.scenes_dir = LGI_SCENES_DIR;
  options.allocation_count = &verification::counted_allocations;
  const verification::Report report = verification::verify_scheme(scheme, options);
  verification::print_report(std::cout, report);
  return report.passed() ? 0 : 1;
} catch (const std::exception& e) {  // lgi's input and run errors: one line, as lgi prints them
  std::cerr << "custom_scheme: " << e.what() << '\n';
  return 2;
}
