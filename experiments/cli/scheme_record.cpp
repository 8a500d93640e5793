#include "experiments/cli/scheme_record.hpp"

namespace lgi::experiments {

const char* scheme_kind(const integrators::SchemeInfo& s) {
  if (s.properties.baseline) return "baseline";
  if (!s.base_scheme.empty()) return "composition";
  if (s.order == 0) return "exact";
  return "lie-group";
}

const char* scheme_support_text(integrators::SceneSupport s) {
  switch (s) {
    case integrators::SceneSupport::free_body_only: return "free bodies";
    case integrators::SceneSupport::conservative_only: return "conservative";
    case integrators::SceneSupport::cardan_only: return "Cardan tops";
    case integrators::SceneSupport::any: break;
  }
  return "all scenes";
}

int scheme_order_on(const integrators::SchemeInfo& s, bool has_torque) {
  return has_torque && s.order_with_torque ? s.order_with_torque : s.order;
}

std::vector<SchemeField> scheme_record(const integrators::SchemeInfo& s, std::optional<bool> scene_has_torque) {
  using Value = decltype(SchemeField::value);
  const auto& p = s.properties;
  std::vector<SchemeField> r{
      {"name", s.name},
      {"order", s.order},
      {"family", s.family},
      {"kind", std::string(scheme_kind(s))},
      {"base", s.base_scheme.empty() ? Value{} : Value{s.base_scheme}},
      {"symplectic", p.symplectic, true},
      {"symmetric", p.symmetric, true},
      {"conserves_energy", p.conserves_energy, true},
      {"conserves_momentum_norm", p.conserves_momentum_norm, true},
      {"conserves_spatial_momentum", p.conserves_spatial_momentum, true},
      {"conserves_vertical_momentum", p.conserves_vertical_momentum, true},
      {"baseline", p.baseline, true},
      {"order_with_torque", scheme_order_on(s, true)}};
  if (scene_has_torque) r.push_back({"order_on_scene", scheme_order_on(s, *scene_has_torque)});
  r.push_back({"implicit", p.implicit, true});
  r.push_back({"adaptive", p.adaptive, true});
  r.push_back({"dense_output", p.dense_output, true});
  r.push_back({"scenes", std::string(scheme_support_text(s.support))});
  // The SIMD lane kernel its facts declare (docs/ensemble.md), or null.
  const char* lanes = integrators::lane_kernel_name(s.lanes.kernel);
  r.push_back({"lane_kernel", *lanes ? Value{std::string(lanes)} : Value{}});
  r.push_back({"reference", s.reference});
  r.push_back({"notes", s.notes});
  return r;
}

}  // namespace lgi::experiments
