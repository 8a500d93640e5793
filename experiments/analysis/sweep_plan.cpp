#include "experiments/analysis/sweep_plan.hpp"

#include "experiments/analysis/level_set_draw.hpp"
#include "experiments/analysis/seeded_random.hpp"

#include <toml++/toml.h>

#include <cmath>
#include <algorithm>
#include <sstream>

#include "experiments/io/gamma_attitude.hpp"
#include "experiments/io/scene_reader.hpp"
#include "experiments/io/scene_toml.hpp"
#include "lie/charts.hpp"
#include "lie/quaternion.hpp"
#include "lie/so3.hpp"

namespace lgi::experiments {

namespace {

using lie::Mat3;
using lie::Vec3;

constexpr std::uint64_t level_set_stream = 1u << 20;

/// Sets key `name` of table `table` (creating the table) to the numbers.
void set_toml_value(toml::table& doc, const std::string& table, const std::string& name, const double* v, int width) {
  if (!doc.contains(table)) doc.insert(table, toml::table{});
  toml::table& t = *doc[table].as_table();
  if (table == "body" && (name == "inertia" || name == "inertia_cm")) {
    t.erase("inertia"), t.erase("inertia_cm"), t.erase("inertia_tensor");
  }
  if (width == 1) {
    t.insert_or_assign(name, v[0]);
  } else {
    toml::array a;
    for (int k = 0; k < width; ++k) a.push_back(v[k]);
    t.insert_or_assign(name, std::move(a));
  }
}

}  // namespace

SweepPlan::SweepPlan(const SweepSpec& spec, const system::Scene& base) : spec_(spec), base_(base) {
  count_ = spec.count();
  for (const auto& v : spec.vary) {
    offsets_.push_back(width_);
    columns_.push_back({v.column, v.width});
    width_ += v.width;
    if (!v.initial_state()) scene_varies_ = true;
  }
  if (spec.level_set) {
    level_offset_ = width_;
    columns_.push_back({"initial.gamma", 3});
    columns_.push_back({"initial.angular_momentum", 3});
    width_ += 6;
  }
  const scene_toml::Reader rd(spec.file);
  // Every grid value once, on the base scene (a combination that is invalid
  // only jointly fails its trajectories with the reason).
  std::vector<double> flat;
  inputs(0, flat);
  for (std::size_t e = 0; e < spec.vary.size(); ++e) {
    const auto& v = spec.vary[e];
    for (const auto& value : v.values) {
      std::vector<double> probe = flat;
      std::copy(value.begin(), value.end(), probe.begin() + offsets_[e]);
      try {
        system::Scene s = scene(probe);
        if (v.initial_state()) (void)initial_state(0, s, probe);
      } catch (const std::exception& err) {
        // The scene reader's message without its file and line (those of the re-read text).
        std::string why = err.what();
        if (const auto at = why.find(": ["); at != std::string::npos) why = why.substr(at + 2);
        rd.fail(v.line, "vary", "key", "\"" + v.key + "\" = " + scene_toml::fmt(value[0]) +
                                           (value.size() > 1 ? ", ..." : "") + " makes the scene " + base.file +
                                           " invalid: " + why);
      }
    }
  }
  if (spec.level_set) {
    if (base.declared_terms() > (base.declared<system::GravityTerm>() ? 1 : 0))
      rd.fail(spec.level_set->line, "level_set", "",
              "the scene " + base.file + " has torques other than gravity; a level set needs an energy of Pi and Gamma alone");
    if (!scene_varies_) {
      const double lowest = sampled_minimum(level_set_body(base), spec.level_set->l);
      if (spec.level_set->h < lowest - 1e-9 * std::max(1.0, std::abs(lowest))) {
        std::vector<double> probe = flat;
        try {
          (void)initial_state(0, base, probe);
        } catch (const TrajectorySetupError&) {
          rd.fail(spec.level_set->line, "level_set", "h",
                  "the level set is empty for this body: at l = " + scene_toml::fmt(spec.level_set->l) + ", H >= " +
                      scene_toml::fmt(lowest) + " for every direction of Gamma (20000 sampled), above h = " +
                      scene_toml::fmt(spec.level_set->h));
        }
      }
    }
  }
}

void SweepPlan::inputs(std::int64_t i, std::vector<double>& flat) const {
  flat.assign(static_cast<std::size_t>(width_), 0.0);
  std::int64_t grid = i / spec_.samples;
  // Mixed radix, the last grid axis fastest.
  for (std::size_t e = spec_.vary.size(); e-- > 0;) {
    const auto& v = spec_.vary[e];
    double* out = flat.data() + offsets_[e];
    if (v.random) {
      CounterRng rng(spec_.seed, i, e + 1);
      for (int k = 0; k < v.width; ++k)
        out[k] = v.low[static_cast<std::size_t>(k)] +
                 rng.uniform() * (v.high[static_cast<std::size_t>(k)] - v.low[static_cast<std::size_t>(k)]);
      continue;
    }
    const auto n = static_cast<std::int64_t>(v.values.size());
    const auto& value = v.values[static_cast<std::size_t>(grid % n)];
    grid /= n;
    std::copy(value.begin(), value.end(), out);
  }
}

bool SweepPlan::same_scene(const std::vector<double>& a, const std::vector<double>& b) const {
  for (std::size_t e = 0; e < spec_.vary.size(); ++e) {
    if (spec_.vary[e].initial_state()) continue;
    for (int k = 0; k < spec_.vary[e].width; ++k)
      if (a[static_cast<std::size_t>(offsets_[e] + k)] != b[static_cast<std::size_t>(offsets_[e] + k)]) return false;
  }
  return true;
}

system::Scene SweepPlan::scene(const std::vector<double>& flat) const {
  if (!scene_varies_) return base_;
  toml::table doc = toml::parse(base_.toml_text, base_.file);
  for (std::size_t e = 0; e < spec_.vary.size(); ++e) {
    const auto& v = spec_.vary[e];
    if (v.initial_state()) continue;
    const double* value = flat.data() + offsets_[e];
    if (v.component == 0) {
      set_toml_value(doc, v.table, v.name, value, v.width);
      continue;
    }
    const toml::array* base = doc[v.table][v.name].as_array();
    if (!base || base->size() != 3)
      throw InputError("the scene " + base_.file + " has no [" + v.table + "] " + v.name + " to take the other components from");
    double full[3];
    for (std::size_t k = 0; k < 3; ++k) full[k] = (*base)[k].value<double>().value_or(0.0);
    full[v.component - 1] = value[0];
    set_toml_value(doc, v.table, v.name, full, 3);
  }
  std::ostringstream text;
  text << doc;
  system::Scene s = parse_scene(text.str(), base_.file + " (with " + spec_.file + "'s varied keys)");
  return s;
}

system::State SweepPlan::initial_state(std::int64_t i, const system::Scene& scene, std::vector<double>& flat) const {
  system::State x = scene.initial;
  if (spec_.level_set) {
    CounterRng rng(spec_.seed, i, level_set_stream);
    Vec3 gamma, Pi;
    const auto& seeds = spec_.level_set->seeds;
    if (!seeds.empty()) {
      const auto& s = seeds[static_cast<std::size_t>(i) % seeds.size()];
      gamma = Vec3(s[0], s[1], s[2]), Pi = Vec3(s[3], s[4], s[5]);
    } else if (!draw_level_point(level_set_body(scene), spec_.level_set->h, spec_.level_set->l,
                                         spec_.level_set->measure, rng, gamma, Pi)) {
      throw TrajectorySetupError("the level set (l, h) was not reached in 1e6 random directions of Gamma");
    }
    x.R = attitude_from_gamma(gamma);
    x.Pi = Pi;
    std::copy(gamma.data(), gamma.data() + 3, flat.begin() + level_offset_);
    std::copy(Pi.data(), Pi.data() + 3, flat.begin() + level_offset_ + 3);
    return x;
  }
  for (std::size_t e = 0; e < spec_.vary.size(); ++e) {
    const auto& v = spec_.vary[e];
    if (!v.initial_state()) continue;
    const double* value = flat.data() + offsets_[e];
    auto replaced = [&](Vec3 base) {
      if (v.component == 0) return Vec3(value[0], value[1], value[2]);
      base[v.component - 1] = value[0];
      return base;
    };
    if (v.name == "angular_momentum") {
      x.Pi = replaced(x.Pi);
    } else if (v.name == "angular_velocity") {
      x.Pi = scene.inertia * replaced(scene.inertia.inverse() * scene.initial.Pi);
    } else if (v.name == "rotation_vector") {
      x.R = lie::exp_so3(replaced(lie::log_so3(scene.initial.R)));
    } else if (v.name == "euler_zxz") {
      const auto e0 = lie::euler_zxz_from_matrix(scene.initial.R).angles;
      const Vec3 a = replaced(Vec3(e0.psi, e0.theta, e0.phi));
      x.R = lie::matrix_from_euler_zxz({a.x(), a.y(), a.z()});
    } else if (v.name == "gamma") {
      const Vec3 g = replaced(scene.initial.R.transpose() * Vec3::UnitZ());
      if (!(g.norm() > 0.0)) throw InputError("initial.gamma is the zero vector (it gives a direction)");
      x.R = attitude_from_gamma(g / g.norm());
    } else if (v.name == "quaternion") {
      const double norm = std::sqrt(value[0] * value[0] + value[1] * value[1] + value[2] * value[2] + value[3] * value[3]);
      if (!(std::abs(norm - 1.0) < scene_toml::unit_norm_tolerance))
        throw InputError("not a unit quaternion: norm " + scene_toml::fmt(norm) + " (tolerance 1e-12)");
      x.R = lie::matrix_from_quat(Eigen::Quaterniond(value[0] / norm, value[1] / norm, value[2] / norm, value[3] / norm));
    }
  }
  return x;
}

}  // namespace lgi::experiments
