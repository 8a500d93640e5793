// Runs a registered scheme on a scene file through an installed lgi and
// prints the largest relative energy error: lgi used as a library.
#include <cstdio>
#include <string>

#include "experiments/io/scene_reader.hpp"
#include "integrators/registry/registry.hpp"
#include "integrators/system/invariants.hpp"

namespace {
class EnergyError final : public lgi::integrators::Observer {
 public:
  explicit EnergyError(const lgi::system::SceneInvariants& inv) : inv_(inv) {}
  void observe(std::int64_t, double, const lgi::system::State& x) override {
    const double e = inv_.energy(x);
    if (!started_) e0_ = e, started_ = true;
    worst = std::max(worst, lgi::system::relative_error(e, e0_));
  }
  double worst = 0.0;

 private:
  const lgi::system::SceneInvariants& inv_;
  double e0_ = 0.0;
  bool started_ = false;
};
}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: run_scene SCENE.toml SCHEME\n");
    return 2;
  }
  const lgi::system::Scene scene = lgi::experiments::read_scene(argv[1]);
  const auto* scheme = lgi::integrators::find_scheme(argv[2]);
  if (!scheme) return 2;
  const lgi::system::AnyModel model = lgi::system::make_model(scene);
  const lgi::system::SceneInvariants invariants(scene, model);
  EnergyError observer(invariants);
  lgi::integrators::RunConfig cfg;
  cfg.t_end = 1.0;
  cfg.dt = 1e-3;
  lgi::system::State x = scene.initial;
  const auto stats = scheme->run(model, x, cfg, observer);
  std::printf("scheme=%s steps=%lld ok=%d energy_error_max=%.3e\n", scheme->name.c_str(),
              static_cast<long long>(stats.steps), stats.ok ? 1 : 0, observer.worst);
  return stats.ok ? 0 : 1;
}
