// lgi schemes: the registry as a table, or as JSON for machines.
#include <algorithm>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "experiments/commands.hpp"
#include <memory>
#include "experiments/exit_status.hpp"
#include "integrators/registry.hpp"

namespace lgi::experiments {
namespace {

std::string json_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out;
}

std::string property_list(const integrators::SchemeProperties& p) {
  std::string s;
  auto add = [&](bool on, const char* name) {
    if (!on) return;
    if (!s.empty()) s += ',';
    s += name;
  };
  add(p.symplectic, "symplectic");
  add(p.symmetric, "symmetric");
  add(p.conserves_energy, "energy");
  add(p.conserves_momentum_norm, "|Pi|");
  add(p.conserves_spatial_momentum, "spatial-momentum");
  add(p.conserves_vertical_momentum, "Pi.Gamma");
  add(p.implicit, "implicit");
  add(p.adaptive, "adaptive");
  return s.empty() ? "-" : s;
}

const char* support_text(integrators::SceneSupport s) {
  switch (s) {
    case integrators::SceneSupport::free_body_only: return "free bodies";
    case integrators::SceneSupport::conservative_only: return "conservative";
    case integrators::SceneSupport::any: break;
  }
  return "all scenes";
}

int list_schemes(bool json) {
  const auto& registry = integrators::scheme_registry();
  if (json) {
    std::cout << "[\n";
    for (std::size_t i = 0; i < registry.size(); ++i) {
      const auto& s = registry[i];
      const auto& p = s.properties;
      std::cout << "  {\"name\": \"" << s.name << "\", \"order\": " << s.order << ", \"family\": \"" << s.family
                << "\", \"symplectic\": " << std::boolalpha << p.symplectic << ", \"symmetric\": " << p.symmetric
                << ", \"conserves_energy\": " << p.conserves_energy
                << ", \"conserves_momentum_norm\": " << p.conserves_momentum_norm
                << ", \"conserves_spatial_momentum\": " << p.conserves_spatial_momentum
                << ", \"conserves_vertical_momentum\": " << p.conserves_vertical_momentum
                << ", \"baseline\": " << p.baseline
                << ", \"order_with_torque\": " << (s.order_with_torque ? s.order_with_torque : s.order)
                << ", \"implicit\": " << p.implicit << ", \"adaptive\": " << p.adaptive << ", \"scenes\": \""
                << support_text(s.support) << "\", \"reference\": \"" << json_escape(s.reference)
                << "\", \"notes\": \"" << json_escape(s.notes) << "\"}" << (i + 1 < registry.size() ? "," : "")
                << '\n';
    }
    std::cout << "]\n";
    return exit_ok;
  }
  // Column widths follow the longest entry, so the table stays aligned as schemes are added.
  std::size_t w_name = 4, w_family = 6, w_props = 10;
  for (const auto& s : registry) {
    w_name = std::max(w_name, s.name.size());
    w_family = std::max(w_family, s.family.size());
    w_props = std::max(w_props, property_list(s.properties).size());
  }
  const auto name_w = static_cast<int>(w_name + 2), family_w = static_cast<int>(w_family + 2),
             props_w = static_cast<int>(w_props + 2);
  std::cout << std::left << std::setw(name_w) << "name" << std::setw(7) << "order" << std::setw(family_w) << "family"
            << std::setw(props_w) << "properties" << std::setw(14) << "scenes"
            << "reference [notes]\n";
  for (const auto& s : registry) {
    std::string order = s.order > 0 ? std::to_string(s.order) : "-";
    if (s.order_with_torque) order += "/" + std::to_string(s.order_with_torque);
    std::cout << std::left << std::setw(name_w) << s.name << std::setw(7) << order << std::setw(family_w) << s.family
              << std::setw(props_w) << property_list(s.properties) << std::setw(14) << support_text(s.support)
              << s.reference << (s.notes.empty() ? "" : " [" + s.notes + "]") << '\n';
  }
  std::cout << "properties: exactly conserved where the quantity is an invariant of the scene "
               "(|Pi|, spatial-momentum: free body; Pi.Gamma: heavy top); order a/b: a on free bodies, b with torques\n";
  return exit_ok;
}

}  // namespace

Subcommand add_schemes_subcommand(CLI::App& app) {
  auto json = std::make_shared<bool>(false);
  auto* sub = app.add_subcommand("schemes", "List every registered scheme with its order and properties");
  sub->add_flag("--json", *json, "Machine-readable JSON");
  return {sub, [json] { return list_schemes(*json); }};
}

}  // namespace lgi::experiments
