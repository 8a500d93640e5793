#include "experiments/commands/periodic/periodic_seeds.hpp"

#include <cmath>
#include <sstream>

#include "experiments/analysis/cardan_section.hpp"
#include "experiments/analysis/section_seeds.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/errors/input_error.hpp"
#include "experiments/io/input_file.hpp"
#include "experiments/io/number_format.hpp"

namespace lgi::experiments {

std::vector<std::pair<Vec6, double>> read_seeds(const std::string& path) {
  std::string text;
  try {  // bounded like every text input (input_file.hpp): /dev/zero or a directory is refused
    text = read_text_input(path, "the seed file");
  } catch (const InputError& e) {
    throw UsageError(std::string("--seed-file: ") + e.what());
  }
  std::istringstream in(text);
  std::vector<std::pair<Vec6, double>> seeds;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    line = line.substr(0, line.find('#'));
    for (char& c : line) c = c == ',' ? ' ' : c;
    std::istringstream s(line);
    std::vector<double> v;
    double d = 0.0;
    while (s >> d) v.push_back(d);
    if (v.empty() && (s.eof() || line.find_first_not_of(" \t\r") == std::string::npos)) continue;
    Vec6 x;
    bool finite = v.size() == 7 && s.eof();
    for (std::size_t k = 0; finite && k < 6; ++k) x(static_cast<int>(k)) = v[k], finite = std::isfinite(v[k]);
    if (!finite || !(v[6] > 0.0) || !std::isfinite(v[6]) || x.tail<3>().norm() == 0.0)
      throw UsageError("--seed-file: " + path + " line " + std::to_string(n) +
                       ": expected Pi1 Pi2 Pi3 Gamma1 Gamma2 Gamma3 T (Gamma nonzero, T > 0)");
    seeds.emplace_back(x, v[6]);
  }
  if (seeds.empty()) throw UsageError("--seed-file: " + path + " holds no seed");
  return seeds;
}

PhaseSection section_of(const PoincareFile& f) {
  PhaseSection s;
  if (f.cardan) {
    s.cardan_factor = 0;
    return s;
  }
  s.kind = f.section == "richter" ? SectionKind::richter : SectionKind::gamma;
  s.axis = f.axis.normalized();
  return s;
}

namespace {

/// Numbers separated by commas; UsageError naming `flag` otherwise.
std::vector<double> numbers(const std::string& text, const std::string& flag, std::size_t count) {
  std::vector<double> v;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    std::size_t used = 0;
    double d = NAN;
    try {
      d = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || item.find_first_not_of(" \t", used) != std::string::npos || !std::isfinite(d))
      throw UsageError(flag + ": '" + text + "' is not a list of numbers");
    v.push_back(d);
  }
  if ((count != 0 && v.size() != count) || v.empty())
    throw UsageError(flag + ": '" + text + "': expected " + (count ? std::to_string(count) + " numbers" : "numbers"));
  return v;
}

/// The time of the returns-th crossing in x's own direction, 0 if none before t_max.
double return_time(const PeriodicFlow& flow, const PhaseSection& sec, const Vec6& x, int returns, double dt,
                   double t_max) {
  const int direction = section_rate(flow, sec, x) >= 0.0 ? 1 : -1;
  bool ok = true;
  const auto cs = section_crossings(flow, sec, x, t_max, dt, static_cast<std::size_t>(returns), direction, ok);
  return cs.size() == static_cast<std::size_t>(returns) ? cs.back().t : 0.0;
}

/// A Cardan seed's phase condition: the factor of S of its piece (±1: q̇2; 2, 3: sin q2).
PhaseSection cardan_phase(std::int64_t piece) {
  PhaseSection s;
  s.cardan_factor = piece == 1 || piece == -1 ? 0 : 1;
  return s;
}

/// A Cardan top's seeds: rows of /events (q, p; q1 set to 0, p1 and H checked against the file's
/// level) and points (x, y, piece) of its section.
std::vector<SectionSeed> cardan_poincare_seeds(const PeriodicFlow& flow, const PoincareFile& f,
                                               const std::vector<double>& rows, const std::vector<std::string>& points) {
  std::vector<SectionSeed> seeds;
  for (const double r : rows) {
    const auto k = static_cast<std::size_t>(r);
    SectionSeed s;
    s.h = f.h;
    s.x << 0.0, f.cardan_angles[k].tail<2>(), f.cardan_momenta[k];
    const double H = flow_invariants(flow, s.x).value(0);
    if (std::abs(s.x(3) - f.l) > 1e-9 * std::max(1.0, std::abs(f.l)) ||
        !(std::abs(H - f.h) <= 1e-4 * std::max(1.0, std::abs(f.h))))
      throw UsageError("--poincare-rows: row " + std::to_string(k) + " has p1 = " + format_general(s.x(3), 17) +
                       ", H = " + format_general(H, 17) + " on the --scene top, not the file's l = " +
                       format_general(f.l, 17) + ", h = " + format_general(f.h, 17));
    s.label = "poincare row " + std::to_string(k);
    s.section = cardan_phase(f.piece[k]);
    // On the level and the sheet before the period guess: a row off the sheet by δ would cross it
    // again at once (t ~ δ) in its own direction.
    if (!project_to_level(flow, s.x, f.h, f.l, &*s.section))
      s.failure = s.label + ": cannot be put on the level and the section";
    seeds.push_back(s);
  }
  for (const std::string& p : points) {
    const std::vector<double> v = numbers(p, "--poincare-point", 3);
    if (v[2] != 1.0 && v[2] != -1.0 && v[2] != 2.0 && v[2] != 3.0)
      throw UsageError("--poincare-point: '" + p + "': on a Cardan top's section the piece must be 1, -1, 2 or 3");
    system::TorusState state;
    if (!cardan_section_state(*flow.cardan, f.l, f.h, v[0], v[1], static_cast<int>(v[2]), state))
      throw UsageError("--poincare-point: '" + p + "' has no state on the section at the file's (l, h)");
    SectionSeed s;
    s.h = f.h;
    s.x = system::stack(state);
    s.label = "poincare point (" + p + ")";
    s.section = cardan_phase(static_cast<std::int64_t>(v[2]));
    seeds.push_back(s);
  }
  return seeds;
}

/// A heavy top's seeds: rows of /events (Π, Γ) and points (φ, ϑ, sheet) of Richter's section.
std::vector<SectionSeed> heavy_poincare_seeds(const HeavyTopBody& body, const PoincareFile& f,
                                              const std::vector<double>& rows, const std::vector<std::string>& points) {
  const PhaseSection sec = section_of(f);
  std::vector<SectionSeed> seeds;
  for (const double r : rows) {
    const auto k = static_cast<std::size_t>(r);
    SectionSeed s;
    s.h = f.h;
    s.x << f.angular_momentum[k], f.gamma[k];
    s.label = "poincare row " + std::to_string(k);
    seeds.push_back(s);
  }
  for (const std::string& p : points) {
    if (sec.kind != SectionKind::richter)
      throw UsageError("--poincare-point: only on Richter's section (the file's section is " + f.section + ")");
    const std::vector<double> v = numbers(p, "--poincare-point", 0);
    if (v.size() != 3 && v.size() != 4)
      throw UsageError("--poincare-point: '" + p + "': expected phi,theta,sheet or phi,theta,sheet,returns");
    if (v[2] != 1.0 && v[2] != -1.0) throw UsageError("--poincare-point: '" + p + "': the sheet must be 1 or -1");
    if (v.size() == 4 && (v[3] != std::floor(v[3]) || v[3] < 1.0 || v[3] > 1000.0))
      throw UsageError("--poincare-point: '" + p + "': the returns must be a whole number in [1, 1000]");
    Vec3 f1, f2;
    section_frame(sec.axis, f1, f2);
    const Vec3 gamma = std::sin(v[1]) * (std::cos(v[0]) * f1 + std::sin(v[0]) * f2) + std::cos(v[1]) * sec.axis;
    Vec3 Pi;
    if (!section_state(body, sec.axis, f.l, f.h, gamma, static_cast<int>(v[2]), Pi))
      throw UsageError("--poincare-point: '" + p + "' has no state on the section at the file's (l, h)");
    SectionSeed s;
    s.h = f.h;
    s.x << Pi, gamma;
    s.label = "poincare point (" + p + ")";
    s.returns = v.size() == 4 ? static_cast<int>(v[3]) : 0;
    seeds.push_back(s);
  }
  return seeds;
}

/// The rows of --poincare-rows, each a row of /events.
std::vector<double> event_rows(const std::string& rows, std::size_t count) {
  std::vector<double> out;
  if (rows.empty()) return out;
  for (const double r : numbers(rows, "--poincare-rows", 0)) {
    if (r != std::floor(r) || r < 0.0 || r >= static_cast<double>(count))
      throw UsageError("--poincare-rows: " + std::to_string(r) + " is not a row of /events (0 to " +
                       std::to_string(count) + " - 1)");
    out.push_back(r);
  }
  return out;
}

}  // namespace

std::vector<SectionSeed> poincare_seeds(const PeriodicFlow& flow, const PoincareFile& f, const std::string& rows,
                                        const std::vector<std::string>& points, int returns, double dt, double t_max) {
  const PhaseSection sec = section_of(f);
  std::vector<SectionSeed> seeds;
  if (flow.cardan)
    seeds = cardan_poincare_seeds(flow, f, event_rows(rows, f.piece.size()), points);
  else
    seeds = heavy_poincare_seeds(flow.body, f, event_rows(rows, f.gamma.size()), points);
  for (SectionSeed& s : seeds) {  // a point's own N (an orbit crossing N times a period) over --returns
    if (!s.failure.empty()) continue;
    const int n = s.returns ? s.returns : returns;
    s.period = return_time(flow, s.section.value_or(sec), s.x, n, dt, t_max * n / returns);
    if (s.period == 0.0)
      s.failure = s.label + ": no " + std::to_string(n) + "-th return to the section before t = " +
                  std::to_string(t_max * n / returns);
  }
  return seeds;
}

}  // namespace lgi::experiments
