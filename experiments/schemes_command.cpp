// lgi schemes: the registry as a table, or as JSON for machines.
#include <iomanip>
#include <iostream>
#include <sstream>

#include "experiments/commands.hpp"
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

}  // namespace

int schemes_command(const SchemesOptions& options) {
  const auto& registry = integrators::scheme_registry();
  if (options.json) {
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
                << ", \"implicit\": " << p.implicit << ", \"adaptive\": " << p.adaptive << ", \"scenes\": \""
                << support_text(s.support) << "\", \"reference\": \"" << json_escape(s.reference)
                << "\", \"notes\": \"" << json_escape(s.notes) << "\"}" << (i + 1 < registry.size() ? "," : "")
                << '\n';
    }
    std::cout << "]\n";
    return exit_ok;
  }
  std::cout << std::left << std::setw(12) << "name" << std::setw(7) << "order" << std::setw(17) << "family"
            << std::setw(38) << "properties (exactly conserved)" << std::setw(13) << "scenes"
            << "reference\n";
  for (const auto& s : registry) {
    std::cout << std::left << std::setw(12) << s.name << std::setw(7) << (s.order > 0 ? std::to_string(s.order) : "-")
              << std::setw(17) << s.family << std::setw(38) << property_list(s.properties) << std::setw(13)
              << support_text(s.support) << s.reference << (s.notes.empty() ? "" : " [" + s.notes + "]") << '\n';
  }
  return exit_ok;
}

}  // namespace lgi::experiments
