#include "experiments/io/sweep_spec.hpp"

#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <string_view>

#include "experiments/io/input_file.hpp"
#include "experiments/io/scene_toml.hpp"

namespace lgi::experiments {

namespace {

using scene_toml::Reader;
using scene_toml::Table;

struct VariableKey {
  std::string_view table, name;
  int width;
};

// The scene keys a sweep may vary (experiments/SWEEPS.md, "What varies").
// initial.gamma is the sweep's own: the attitude with Γ = Rᵀe3 along it and ψ = 0.
// The suspension.* keys make sense on a Cardan scene only (lgi chaos-map --vary).
constexpr std::array<VariableKey, 27> variable_keys{{
    {"initial", "angular_momentum", 3}, {"initial", "angular_velocity", 3}, {"initial", "quaternion", 4},
    {"initial", "rotation_vector", 3},  {"initial", "euler_zxz", 3},        {"initial", "gamma", 3},
    {"body", "inertia", 3},             {"body", "inertia_cm", 3},          {"body", "center_of_mass", 3},
    {"body", "mass", 1},                {"gravity", "g", 1},                {"spring", "stiffness", 1},
    {"spring", "damping", 1},           {"spring", "rest_quaternion", 4},   {"drive", "torque_amplitude", 3},
    {"drive", "angular_frequency", 1},  {"drive", "phase", 1},              {"magnetic", "dipole_moment", 3},
    {"magnetic", "field", 3},           {"body", "allow_unphysical", 0},    {"suspension", "tilt", 1},
    {"suspension", "outer_inertia", 1}, {"suspension", "inner_inertia", 3}, {"suspension", "outer_mass", 1},
    {"suspension", "outer_center", 3},  {"suspension", "inner_mass", 1},    {"suspension", "inner_center", 3},
}};

std::string variable_key_list() {
  std::string s;
  for (const auto& k : variable_keys) {
    if (k.width == 0) continue;
    if (!s.empty()) s += ", ";
    s += std::string(k.table) + "." + std::string(k.name);
  }
  return s;
}

constexpr std::array<std::string_view, 16> top_keys{
    "name",       "description",   "scene",            "scheme", "dt",        "tol",  "t_end", "seed",
    "samples",    "chunk",         "max_events",       "monitor_every", "trajectory_every", "vary", "level_set", "event"};
constexpr std::array<std::string_view, 6> vary_keys{"key", "component", "values", "linspace", "logspace", "uniform"};
constexpr std::array<std::string_view, 3> level_keys{"h", "l", "measure"};
constexpr std::array<std::string_view, 5> event_keys{"name", "quantity", "component", "value", "direction"};

std::int64_t integer(const Table& t, std::string_view key, const toml::node& n, std::int64_t min) {
  const auto* i = n.as_integer();
  if (!i) t.fail(n, key, "expected an integer, got " + scene_toml::type_name(n));
  if (i->get() < min) t.fail(n, key, "must be at least " + std::to_string(min) + ", got " + std::to_string(i->get()));
  return i->get();
}

std::vector<double> value_of_width(const Table& t, std::string_view key, const toml::node& n, int width,
                                   const std::string& element) {
  if (width == 1) return {t.number(key, n, element)};
  return t.numbers(key, n, static_cast<std::size_t>(width), element);
}

/// values / linspace / logspace / uniform: exactly one.
void read_values(const Table& t, VaryEntry& v) {
  const auto which = t.one_of(std::array<std::string_view, 4>{"values", "linspace", "logspace", "uniform"}, "range");
  if (!which) t.fail_here("values", "missing: give one of values, linspace, logspace, uniform");
  const toml::node& n = *t.get(*which);
  if (*which == "values") {
    const auto* a = n.as_array();
    if (!a) t.fail(n, "values", "expected an array of values, got " + scene_toml::type_name(n));
    if (a->empty()) t.fail(n, "values", "empty: give at least one value");
    v.values.reserve(a->size());
    for (std::size_t i = 0; i < a->size(); ++i)
      v.values.push_back(value_of_width(t, "values", (*a)[i], v.width, "value " + std::to_string(i + 1) + ": "));
    return;
  }
  if (*which == "uniform") {
    v.random = true;
    const auto* a = n.as_array();
    if (!a || a->size() != 2) t.fail(n, "uniform", "expected [low, high]");
    v.low = value_of_width(t, "uniform", (*a)[0], v.width, "low: ");
    v.high = value_of_width(t, "uniform", (*a)[1], v.width, "high: ");
    for (std::size_t i = 0; i < v.low.size(); ++i)
      if (!(v.low[i] <= v.high[i])) t.fail(n, "uniform", "empty range: low > high");
    return;
  }
  // linspace / logspace = [from, to, count]
  if (v.width != 1) t.fail(n, *which, "needs a scalar (a number key, or one component of a vector key)");
  const auto* a = n.as_array();
  if (!a || a->size() != 3) t.fail(n, *which, "expected [from, to, count]");
  const double from = t.number(*which, (*a)[0], "from: "), to = t.number(*which, (*a)[1], "to: ");
  const auto* c = (*a)[2].as_integer();
  if (!c) t.fail(n, *which, "count: expected an integer, got " + scene_toml::type_name((*a)[2]));
  if (c->get() < 0) t.fail(n, *which, "count: negative (" + std::to_string(c->get()) + ")");
  if (c->get() == 0) t.fail(n, *which, "count: 0 gives an empty range");
  if (c->get() > 10000000) t.fail(n, *which, "count: more than 10000000 points on one axis");
  const bool log = *which == "logspace";
  if (log && !(from > 0.0 && to > 0.0)) t.fail(n, *which, "from and to must be > 0");
  const std::int64_t count = c->get();
  for (std::int64_t i = 0; i < count; ++i) {
    const double s = count == 1 ? 0.0 : static_cast<double>(i) / static_cast<double>(count - 1);
    const double x = log ? std::exp(std::log(from) + s * (std::log(to) - std::log(from))) : from + s * (to - from);
    v.values.push_back({i == count - 1 && count > 1 ? to : (i == 0 ? from : x)});
  }
}

VaryEntry read_vary(const Reader& rd, const toml::table& tbl) {
  const Table t{rd, "vary", &tbl, scene_toml::line_of(tbl)};
  t.check_keys(vary_keys);
  VaryEntry v;
  v.line = t.line.value_or(0);
  const toml::node* key = t.get("key");
  if (!key) t.fail_here("key", "missing (the scene key to vary, e.g. \"initial.angular_momentum\")");
  v.key = t.string("key", *key);
  const auto dot = v.key.find('.');
  if (dot != std::string::npos) {
    v.table = v.key.substr(0, dot);
    v.name = v.key.substr(dot + 1);
  }
  const VariableKey* known = nullptr;
  for (const auto& k : variable_keys)
    if (k.width > 0 && k.table == v.table && k.name == v.name) known = &k;
  if (!known) t.fail(*key, "key", "\"" + v.key + "\" cannot be varied (the keys: " + variable_key_list() + ")");
  v.width = known->width;
  v.column = v.key;
  if (const toml::node* c = t.get("component")) {
    if (v.width != 3) t.fail(*c, "component", "only for keys of 3 numbers");
    v.component = static_cast<int>(integer(t, "component", *c, 1));
    if (v.component > 3) t.fail(*c, "component", "must be 1, 2 or 3");
    v.width = 1;
    v.column += "_" + std::to_string(v.component);
  }
  read_values(t, v);
  if (v.random && (v.name == "quaternion" || v.name == "rest_quaternion"))
    t.fail(*t.get("uniform"), "uniform", "a uniform box of quaternions is not on the unit sphere; vary a rotation_vector or gamma");
  return v;
}

EventSpec read_event(const Reader& rd, const toml::table& tbl) {
  const Table t{rd, "event", &tbl, scene_toml::line_of(tbl)};
  t.check_keys(event_keys);
  EventSpec e;
  const toml::node* q = t.get("quantity");
  if (!q) t.fail_here("quantity", "missing (angular_momentum, angular_velocity, gamma or gamma_rate)");
  const std::string quantity = t.string("quantity", *q);
  if (quantity == "angular_momentum") e.quantity = EventSpec::Quantity::angular_momentum;
  else if (quantity == "angular_velocity") e.quantity = EventSpec::Quantity::angular_velocity;
  else if (quantity == "gamma") e.quantity = EventSpec::Quantity::gamma;
  else if (quantity == "gamma_rate") e.quantity = EventSpec::Quantity::gamma_rate;
  else t.fail(*q, "quantity", "\"" + quantity + "\": expected angular_momentum, angular_velocity, gamma or gamma_rate");
  const toml::node* c = t.get("component");
  if (!c) t.fail_here("component", "missing (1, 2 or 3)");
  e.component = static_cast<int>(integer(t, "component", *c, 1));
  if (e.component > 3) t.fail(*c, "component", "must be 1, 2 or 3");
  e.axis[static_cast<std::size_t>(e.component - 1)] = 1.0;
  e.value = t.optional_number("value").value_or(0.0);
  std::string dir = "both";
  if (const toml::node* d = t.get("direction")) {
    dir = t.string("direction", *d);
    if (dir != "rising" && dir != "falling" && dir != "both")
      t.fail(*d, "direction", "\"" + dir + "\": expected rising, falling or both");
  }
  e.direction = dir == "rising" ? 1 : dir == "falling" ? -1 : 0;
  const char* symbol = e.quantity == EventSpec::Quantity::gamma        ? "gamma"
                       : e.quantity == EventSpec::Quantity::gamma_rate ? "gamma_rate"
                       : e.quantity == EventSpec::Quantity::angular_momentum ? "Pi" : "Omega";
  e.name = std::string(symbol) + std::to_string(e.component) + "_" + dir;
  if (const toml::node* n = t.get("name")) e.name = t.string("name", *n);
  return e;
}

void check_combinations(const Table& root, const SweepSpec& s) {
  std::set<std::string> columns, motion, attitude;
  for (const auto& v : s.vary) {
    if (!columns.insert(v.column).second)
      root.rd.fail(v.line, "vary", "key", "\"" + v.column + "\" is varied twice");
    if (v.table != "initial") continue;
    if (s.level_set)
      root.rd.fail(v.line, "vary", "key", "\"" + v.key + "\" conflicts with [level_set], which draws the initial state");
    (v.name == "angular_momentum" || v.name == "angular_velocity" ? motion : attitude).insert(v.name);
  }
  if (motion.size() > 1)
    root.rd.fail(std::nullopt, "vary", "key", "vary at most one of initial.angular_momentum and initial.angular_velocity");
  if (attitude.size() > 1)
    root.rd.fail(std::nullopt, "vary", "key", "vary at most one of initial.quaternion, rotation_vector, euler_zxz, gamma");
  const bool any_random = s.level_set.has_value() ||
                          std::any_of(s.vary.begin(), s.vary.end(), [](const VaryEntry& v) { return v.random; });
  if (s.samples > 1 && !any_random)
    root.fail(*root.get("samples"), "samples",
              "> 1 repeats identical trajectories: it needs a [[vary]] with uniform, or [level_set]");
  long double total = static_cast<long double>(s.samples);
  for (const auto& v : s.vary)
    if (!v.random) total *= static_cast<long double>(v.values.size());
  if (total > 1e9L) root.rd.fail(std::nullopt, "", "vary", "more than 1e9 trajectories");
}

}  // namespace

const char* level_measure_name(LevelMeasure m) { return m == LevelMeasure::liouville ? "liouville" : "uniform"; }

std::optional<LevelMeasure> level_measure_from_name(const std::string& name) {
  if (name == "liouville") return LevelMeasure::liouville;
  if (name == "uniform") return LevelMeasure::uniform;
  return std::nullopt;
}

std::int64_t SweepSpec::grid_points() const {
  std::int64_t n = 1;
  for (const auto& v : vary)
    if (!v.random) n *= static_cast<std::int64_t>(v.values.size());
  return n;
}

SweepSpec parse_sweep_spec(const std::string& text, const std::string& path) {
  const Reader rd(path);
  toml::table doc;
  try {
    doc = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    rd.fail(scene_toml::line_of(e.source()), "", "TOML syntax error", std::string(e.description()));
  }
  const Table root{rd, "", &doc, std::nullopt};
  root.check_keys(top_keys, "vary, level_set, event");
  SweepSpec s;
  s.file = path;
  s.text = text;
  const toml::node* scene = root.get("scene");
  if (!scene) root.fail_here("scene", "missing (the base scene file, relative to this spec)");
  const std::string scene_file = root.string("scene", *scene);
  if (scene_file.empty()) root.fail(*scene, "scene", "empty");
  const auto slash = path.rfind('/');
  s.scene_path = scene_file.front() == '/' || slash == std::string::npos ? scene_file : path.substr(0, slash + 1) + scene_file;
  const toml::node* scheme = root.get("scheme");
  if (!scheme) root.fail_here("scheme", "missing (a name from `lgi schemes`)");
  s.scheme = root.string("scheme", *scheme);
  s.dt = root.optional_number("dt");
  s.tol = root.optional_number("tol");
  s.t_end = root.optional_number("t_end");
  if (s.dt && s.tol) root.fail(*root.get("tol"), "tol", "give dt (fixed-step schemes) or tol (adaptive), not both");
  if (s.dt && !(*s.dt > 0.0)) root.fail(*root.get("dt"), "dt", "must be > 0");
  if (s.tol && !(*s.tol > 0.0)) root.fail(*root.get("tol"), "tol", "must be > 0");
  if (s.t_end && !(*s.t_end > 0.0)) root.fail(*root.get("t_end"), "t_end", "must be > 0");
  if (const toml::node* n = root.get("seed")) s.seed = static_cast<std::uint64_t>(integer(root, "seed", *n, 0));
  if (const toml::node* n = root.get("samples")) s.samples = integer(root, "samples", *n, 1);
  if (const toml::node* n = root.get("chunk")) s.chunk = integer(root, "chunk", *n, 1);
  if (const toml::node* n = root.get("max_events")) s.max_events = integer(root, "max_events", *n, 0);
  if (const toml::node* n = root.get("monitor_every")) s.monitor_every = integer(root, "monitor_every", *n, 1);
  if (const toml::node* n = root.get("trajectory_every")) {
    s.trajectory_every = integer(root, "trajectory_every", *n, 1);
    if (s.trajectory_every % s.monitor_every != 0)
      root.fail(*n, "trajectory_every",
                "must be a multiple of monitor_every (" + std::to_string(s.monitor_every) + "): states are seen every monitor_every steps");
  }

  if (const toml::node* n = root.get("vary")) {
    const auto* a = n->as_array();
    if (!a || !a->is_array_of_tables()) root.fail(*n, "vary", "expected [[vary]] tables");
    for (const auto& e : *a) s.vary.push_back(read_vary(rd, *e.as_table()));
  }
  if (const toml::node* n = root.get("level_set")) {
    (void)n;
    const Table t = scene_toml::sub_table(root, "level_set");
    t.check_keys(level_keys);
    s.level_set = LevelSetSpec{t.required_number("h", "the energy H of the level set"),
                               t.required_number("l", "the momentum Pi.Gamma of the level set"), t.line.value_or(0),
                               LevelMeasure::liouville, {}};
    if (const toml::node* m = t.get("measure")) {
      const std::string name = t.string("measure", *m);
      const auto measure = level_measure_from_name(name);
      if (!measure) t.fail(*m, "measure", "\"" + name + "\": expected liouville or uniform");
      s.level_set->measure = *measure;
    }
  }
  if (const toml::node* n = root.get("event")) {
    const auto* a = n->as_array();
    if (!a || !a->is_array_of_tables()) root.fail(*n, "event", "expected [[event]] tables");
    for (const auto& e : *a) s.events.push_back(read_event(rd, *e.as_table()));
  }
  check_combinations(root, s);
  return s;
}

SweepSpec read_sweep_spec(const std::string& path) {
  return parse_sweep_spec(read_text_input(path, "sweep spec"), path);
}

}  // namespace lgi::experiments
