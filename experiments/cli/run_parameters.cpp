// The /parameters record of a run; see run_parameters.hpp.
#include "experiments/cli/run_parameters.hpp"

namespace lgi::experiments {

ResultAttributes scene_parameters(const system::Scene& scene) {
  ResultAttributes a;
  a.text = {{"scene_file", scene.file}, {"scene_name", scene.name}, {"scene_toml", scene.toml_text}};
  return a;
}

ResultAttributes run_parameters(const system::Scene& scene, const integrators::SchemeInfo& scheme,
                                const integrators::RunConfig& cfg, const std::string& command_line) {
  ResultAttributes a = scene_parameters(scene);
  a.text["scheme"] = scheme.name;
  a.text["command_line"] = command_line;
  if (scheme.properties.adaptive) {
    a.number["tol"] = cfg.tol;
    if (cfg.dt > 0.0) a.number["dt"] = cfg.dt;  // 0: the scheme chose its first step
  } else {
    a.number["dt"] = cfg.dt;
  }
  a.number["t_end"] = cfg.t_end;
  return a;
}

}  // namespace lgi::experiments
