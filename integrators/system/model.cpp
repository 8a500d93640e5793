#include "integrators/system/model.hpp"

namespace lgi::system {

AnyModel make_model(const Scene& scene) {
  const Inertia inertia = make_inertia(scene.inertia);
  if (scene.is_free_body()) return FreeBody{inertia, {}};
  SceneModel model{inertia, {}};
  const BodyProperties body = scene.body();
  std::apply(
      [&](auto&... slot) {
        auto fill = [&](auto& declared) {
          using Term = typename std::decay_t<decltype(declared)>::Term;
          if (const auto& p = scene.declared<Term>()) {
            declared.term = Term::from_scene(*p, body);
            declared.active = true;
          }
        };
        (fill(slot), ...);
      },
      model.terms);
  return model;
}

}  // namespace lgi::system
