// lgi schemes: the registry as a compact table (--long adds references and
// notes), filtered by family or by the scenes a scheme applies to, or as JSON.
#include <algorithm>
#include <cctype>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include "experiments/commands/all_commands.hpp"
#include "experiments/cli/scheme_lookup.hpp"
#include "experiments/cli/scheme_record.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/io/scene_reader.hpp"
#include "integrators/registry/registry.hpp"

namespace lgi::experiments {
namespace {

using integrators::SchemeInfo;

struct SchemesOptions {
  bool json = false;
  bool long_view = false;
  std::string family;
  std::string scene;
};

std::string json_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out;
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

/// The properties a scheme claims, and "lanes" where it has an ensemble kernel; the compact
/// view abbreviates them (its legend says how).
std::string property_list(const SchemeInfo& scheme, bool long_names) {
  const integrators::SchemeProperties& p = scheme.properties;
  std::string s;
  auto add = [&](bool on, const char* full, const char* brief) {
    if (!on) return;
    if (!s.empty()) s += ',';
    s += long_names ? full : brief;
  };
  add(p.symplectic, "symplectic", "sympl");
  add(p.symmetric, "symmetric", "sym");
  add(p.conserves_energy, "energy", "H");
  add(p.conserves_momentum_norm, "|Pi|", "|Pi|");
  add(p.conserves_spatial_momentum, "spatial-momentum", "m");
  add(p.conserves_vertical_momentum, "Pi.Gamma", "Pi.G");
  add(p.implicit, "implicit", "impl");
  add(p.adaptive, "adaptive", "adapt");
  add(p.dense_output, "dense-output", "dense");
  add(scheme.lanes.kernel != integrators::LaneKernel::none, "lanes", "lanes");
  return s.empty() ? "-" : s;
}

const char* support_text(integrators::SceneSupport s) { return scheme_support_text(s); }
const char* kind_of(const SchemeInfo& s) { return scheme_kind(s); }

/// The scene a listing is restricted to: the schemes that apply, and their order there.
struct SceneFilter {
  system::AnyModel model;
  bool has_torque = false;
  std::string file;
  bool cardan = false;  // a [suspension] scene: only the T³ schemes apply
};

std::optional<SceneFilter> scene_filter(const std::string& path) {
  if (path.empty()) return std::nullopt;
  const system::Scene scene = read_scene(path);
  SceneFilter f{system::make_model(scene), false, scene.file, scene.suspension.has_value()};
  f.has_torque = std::visit([](const auto& m) { return std::decay_t<decltype(m)>::has_torque; }, f.model);
  return f;
}

int order_on(const SchemeInfo& s, bool has_torque) { return scheme_order_on(s, has_torque); }

std::vector<const SchemeInfo*> selected(const SchemesOptions& o, const std::optional<SceneFilter>& scene) {
  std::vector<const SchemeInfo*> out;
  const std::string family = lower(o.family);
  for (const SchemeInfo* s : listed_schemes()) {
    if (!family.empty() && lower(s->family).find(family) == std::string::npos && lower(kind_of(*s)) != family) continue;
    const bool t3 = s->support == integrators::SceneSupport::cardan_only;
    if (scene && (scene->cardan ? !t3 : !integrators::unsupported_reason(*s, scene->model).empty())) continue;
    out.push_back(s);
  }
  return out;
}

/// One field of a scheme's record as JSON text.
std::string json_value(const SchemeField& f) {
  struct Text {
    std::string operator()(std::monostate) const { return "null"; }
    std::string operator()(bool b) const { return b ? "true" : "false"; }
    std::string operator()(int i) const { return std::to_string(i); }
    // Appended, not '"' + ... + '"': GCC 12 warns falsely (-Wrestrict) on the inlined
    // operator+ of a literal and a temporary when this unit is compiled in a unity batch.
    std::string operator()(const std::string& s) const {
      std::string quoted = "\"";
      quoted += json_escape(s);
      quoted += '"';
      return quoted;
    }
  };
  return std::visit(Text{}, f.value);
}

void print_json(const std::vector<const SchemeInfo*>& schemes, const std::optional<SceneFilter>& scene) {
  std::cout << "[\n";
  for (std::size_t i = 0; i < schemes.size(); ++i) {
    const std::vector<SchemeField> record =
        scheme_record(*schemes[i], scene ? std::optional<bool>(scene->has_torque) : std::nullopt);
    std::cout << "  {";
    for (std::size_t k = 0; k < record.size(); ++k)
      std::cout << (k ? ", " : "") << '"' << record[k].key << "\": " << json_value(record[k]);
    std::cout << '}' << (i + 1 < schemes.size() ? "," : "") << '\n';
  }
  std::cout << "]\n";
}

std::string order_text(const SchemeInfo& s, const std::optional<SceneFilter>& scene) {
  if (s.order == 0) return "-";
  if (scene) return std::to_string(order_on(s, scene->has_torque));
  std::string order = std::to_string(s.order);
  if (s.order_with_torque) order += "/" + std::to_string(s.order_with_torque);
  return order;
}

void print_table(const std::vector<const SchemeInfo*>& schemes, const std::optional<SceneFilter>& scene,
                 bool long_view) {
  // Column widths follow the longest entry, so the table stays aligned as schemes are added.
  std::size_t w_name = 4, w_family = 6, w_props = 10;
  bool any_split_order = false;
  for (const SchemeInfo* s : schemes) {
    w_name = std::max(w_name, s->name.size());
    w_family = std::max(w_family, s->family.size());
    w_props = std::max(w_props, property_list(*s, long_view).size());
    any_split_order = any_split_order || s->order_with_torque != 0;
  }
  const auto col = [](std::size_t w) { return static_cast<int>(w + 2); };
  std::cout << std::left << std::setw(col(w_name)) << "name" << std::setw(7) << "order" << std::setw(col(w_family))
            << "family" << std::setw(col(w_props)) << "properties" << "scenes\n";
  for (const SchemeInfo* s : schemes) {
    std::cout << std::left << std::setw(col(w_name)) << s->name << std::setw(7) << order_text(*s, scene)
              << std::setw(col(w_family)) << s->family << std::setw(col(w_props))
              << property_list(*s, long_view)
              << support_text(s->support) << '\n';
    if (long_view) {
      std::cout << "    reference: " << s->reference << '\n';
      if (!s->notes.empty()) std::cout << "    notes: " << s->notes << '\n';
    }
  }
  if (scene)
    std::cout << schemes.size() << " schemes apply to " << scene->file << "; order: on this scene ("
              << (scene->has_torque ? "with torque" : "free body") << ")\n";
  else if (any_split_order)
    std::cout << "order a/b: a on free bodies, b on scenes with torques\n";
  if (long_view)
    std::cout << "properties: exactly conserved where the quantity is an invariant of the scene "
                 "(|Pi|, spatial-momentum: free body; Pi.Gamma: heavy top); lanes: an ensemble kernel "
                 "(lgi sweep steps its trajectories in SIMD lanes, docs/ensemble.md)\n";
  else
    std::cout << "properties: sympl(ectic), sym(metric), impl(icit), adapt(ive), dense (output inside a step),\n"
                 "  lanes (an ensemble kernel: lgi sweep steps its trajectories in SIMD lanes);\n"
                 "  conserved exactly where an invariant:\n"
                 "  H energy, |Pi|, m spatial momentum (free body), Pi.G = Pi.Gamma (heavy top; p1 of a Cardan top)\n"
                 "--long: full names, references and notes\n";
}

int list_schemes(const SchemesOptions& o) {
  const std::optional<SceneFilter> scene = scene_filter(o.scene);
  const std::vector<const SchemeInfo*> schemes = selected(o, scene);
  if (schemes.empty() && !o.family.empty())
    throw UsageError("--family: no scheme's family or kind matches '" + o.family + "' (lgi schemes lists them)");
  if (o.json) print_json(schemes, scene);
  else print_table(schemes, scene, o.long_view);
  return exit_ok;
}

}  // namespace

Subcommand add_schemes_subcommand(CLI::App& app, const CommandContext& /*context*/) {
  auto o = std::make_shared<SchemesOptions>();
  auto* sub = app.add_subcommand("schemes", "List the registered schemes with their order, family and properties");
  sub->add_flag("--json", o->json, "Machine-readable JSON (every field, with \"kind\" and \"base\")");
  sub->add_flag("--long", o->long_view, "Add each scheme's reference and notes");
  sub->add_option("--family", o->family,
                  "Only schemes whose family contains TEXT (case-insensitive), or of this kind: lie-group, "
                  "composition, baseline, exact");
  sub->add_option("--scene", o->scene, "Only the schemes that apply to this scene file, with their order on it");
  return {sub, [o] { return list_schemes(*o); }};
}

}  // namespace lgi::experiments
