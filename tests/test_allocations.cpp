// Steps allocate nothing: for every registered scheme, the number of heap
// allocations of a run does not depend on its number of steps (per-run
// set-up may allocate, a step may not). Counted by replacing the global
// operator new in this test executable.
#include <atomic>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <new>

#include "experiments/io/scene_reader.hpp"
#include "integrators/registry.hpp"

namespace {
std::atomic<long> allocations{0};
}

// Every replaceable form of new and delete (scalar, array, nothrow, sized)
// that is not over-aligned, so that allocation and release always pair
// malloc with free (AddressSanitizer checks the pairing).
namespace {
void* counted_malloc(std::size_t n) noexcept {
  allocations.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(n ? n : 1);
}
void* counted_or_throw(std::size_t n) {
  if (void* p = counted_malloc(n)) return p;
  throw std::bad_alloc();
}
}  // namespace

void* operator new(std::size_t n) { return counted_or_throw(n); }
void* operator new[](std::size_t n) { return counted_or_throw(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept { return counted_malloc(n); }
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept { return counted_malloc(n); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }

using namespace lgi;

namespace {
long allocations_of_run(const integrators::SchemeInfo& scheme, const system::AnyModel& model,
                        const system::Scene& scene, std::int64_t steps, double h) {
  system::State x = scene.initial;
  integrators::NullObserver none;
  integrators::RunConfig cfg{0.0, static_cast<double>(steps) * h, h, 1e-8, 1};
  const long before = allocations.load();
  const auto stats = scheme.run(model, x, cfg, none);
  const long after = allocations.load();
  INFO(scheme.name << ": " << stats.status);
  REQUIRE(stats.ok);
  return after - before;
}
}  // namespace

TEST_CASE("no scheme allocates per step", "[allocations]") {
  for (const char* file : {"free_body_hlw.toml", "heavy_top_trindade_1.toml", "stiff_damped_spring.toml"}) {
    const system::Scene scene = experiments::read_scene(std::string(LGI_SCENES_DIR) + "/" + file);
    const system::AnyModel model = system::make_model(scene);
    const double h = scene.dt.value_or(1e-3);
    for (const auto& scheme : integrators::scheme_registry()) {
      if (!integrators::unsupported_reason(scheme, model).empty()) continue;
      // Explicit schemes blow up there; compositions take negative substeps,
      // which run the damper backward (composition.hpp).
      if (std::string(file) == "stiff_damped_spring.toml" &&
          (!scheme.properties.implicit || scheme.name.find('@') != std::string::npos))
        continue;
      // Odeint's bulirsch_stoer resizes its extrapolation tables when it
      // changes order: that is the library's, not ours, and it is documented
      // in `lgi schemes`.
      if (scheme.properties.baseline && scheme.name.ends_with("/bs")) continue;
      // The identity start of free_body_hlw is the Euler-angle singularity
      // itself (theta = 0): the run refuses it, by design.
      if (scheme.properties.euler_angle_chart && std::string(file) == "free_body_hlw.toml") continue;
      const long few = allocations_of_run(scheme, model, scene, 10, h);
      const long many = allocations_of_run(scheme, model, scene, 1000, h);
      INFO(scheme.name << " on " << file << ": " << few << " allocations for 10 steps, " << many << " for 1000");
      CHECK(many == few);
    }
  }
}
