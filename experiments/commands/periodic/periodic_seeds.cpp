#include "experiments/commands/periodic/periodic_seeds.hpp"

#include <cmath>
#include <sstream>

#include "experiments/analysis/section_seeds.hpp"
#include "experiments/errors/exit_status.hpp"
#include "experiments/errors/input_error.hpp"
#include "experiments/io/input_file.hpp"

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
double return_time(const HeavyTopBody& body, const PhaseSection& sec, const Vec6& x, int returns, double dt,
                   double t_max) {
  const int direction = section_gradient(body, sec, x).dot(euler_poisson_field(body, x)) >= 0.0 ? 1 : -1;
  bool ok = true;
  const auto cs = section_crossings(body, sec, x, t_max, dt, static_cast<std::size_t>(returns), direction, ok);
  return cs.size() == static_cast<std::size_t>(returns) ? cs.back().t : 0.0;
}

}  // namespace

std::vector<SectionSeed> poincare_seeds(const HeavyTopBody& body, const PoincareFile& f, const std::string& rows,
                                        const std::vector<std::string>& points, int returns, double dt, double t_max) {
  const PhaseSection sec = section_of(f);
  std::vector<SectionSeed> seeds;
  if (!rows.empty())
    for (const double r : numbers(rows, "--poincare-rows", 0)) {
      if (r != std::floor(r) || r < 0.0 || r >= static_cast<double>(f.gamma.size()))
        throw UsageError("--poincare-rows: " + std::to_string(r) + " is not a row of /events (0 to " +
                         std::to_string(f.gamma.size()) + " - 1)");
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
  for (SectionSeed& s : seeds) {  // a point's own N (an orbit crossing N times a period) over --returns
    const int n = s.returns ? s.returns : returns;
    s.period = return_time(body, sec, s.x, n, dt, t_max * n / returns);
    if (s.period == 0.0)
      s.failure = s.label + ": no " + std::to_string(n) + "-th return to the section before t = " +
                  std::to_string(t_max * n / returns);
  }
  return seeds;
}

}  // namespace lgi::experiments
