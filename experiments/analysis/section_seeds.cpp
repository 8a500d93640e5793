// lgi poincare --seeds (section_seeds.hpp; experiments/POINCARE.md "Seeds").
#include "experiments/analysis/section_seeds.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include "experiments/errors/exit_status.hpp"
#include "experiments/errors/input_error.hpp"
#include "experiments/io/input_file.hpp"

namespace lgi::experiments {

namespace {

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  std::string cell;
  while (std::getline(in, cell, ',')) {
    const auto a = cell.find_first_not_of(" \t\r"), b = cell.find_last_not_of(" \t\r");
    out.push_back(a == std::string::npos ? "" : cell.substr(a, b - a + 1));
  }
  return out;
}

double number_in(const std::string& cell, const std::string& where) {
  std::size_t used = 0;
  double x = 0.0;
  try {
    x = std::stod(cell, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != cell.size() || !std::isfinite(x))
    throw UsageError("--seeds: " + where + ": \"" + cell + "\" is not a finite number");
  return x;
}

const std::vector<std::string> point_header = {"phi", "theta", "sheet"};
const std::vector<std::string> state_header = {"gamma_1",
                                               "gamma_2",
                                               "gamma_3",
                                               "angular_momentum_1",
                                               "angular_momentum_2",
                                               "angular_momentum_3"};

}  // namespace

bool section_state(const HeavyTopBody& body, const Vec3& e, double l, double h, const Vec3& gamma, int sheet,
                   Vec3& Pi) {
  const Mat3 J_inv = body.J.inverse();
  const Vec3 a = J_inv * e.cross(gamma);
  const Vec3 n = gamma.cross(a);
  if (!(n.norm() > 1e-12 * a.norm()) || !(a.norm() > 0.0)) return false;
  // Π0 = αΓ + βa with Π0·Γ = l, Π0·a = 0 (|Γ| = 1).
  const double ga = gamma.dot(a), aa = a.dot(a), det = aa - ga * ga;
  const Vec3 Pi0 = (l * aa / det) * gamma - (l * ga / det) * a;
  const double qa = 0.5 * n.dot(J_inv * n), qb = n.dot(J_inv * Pi0);
  const double qc = 0.5 * Pi0.dot(J_inv * Pi0) + body.weight.dot(gamma) - h;
  const double disc = qb * qb - 4.0 * qa * qc;
  if (!(disc >= 0.0)) return false;
  const double root = std::sqrt(disc);
  // The two roots without cancellation (Numerical Recipes §5.6).
  const double q = -0.5 * (qb + (qb < 0.0 ? -root : root));
  const double s1 = q / qa, s2 = q != 0.0 ? qc / q : s1;
  for (const double s : {s1, s2}) {
    const Vec3 P = Pi0 + s * n;
    if (section_point(SectionKind::richter, e, gamma, P, J_inv).sheet == sheet) {
      Pi = P;
      return true;
    }
  }
  return false;
}

std::vector<SeedState> read_section_seeds(const std::string& path, const HeavyTopBody& body, SectionKind kind,
                                          const Vec3& e, double l, double h) {
  std::string text;
  try {
    text = read_text_input(path, "the seed file");
  } catch (const InputError& error) {
    throw UsageError(std::string("--seeds: ") + error.what());
  }
  std::istringstream in(text);
  std::vector<SeedState> out;
  std::vector<std::string> header;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[line.find_first_not_of(" \t\r")] == '#') continue;
    const std::vector<std::string> cells = split_csv(line);
    const std::string where = path + " line " + std::to_string(number);
    if (header.empty()) {
      if (cells != point_header && cells != state_header)
        throw UsageError("--seeds: " + where + ": the header must be phi,theta,sheet or gamma_1,gamma_2,gamma_3,"
                         "angular_momentum_1,angular_momentum_2,angular_momentum_3");
      if (cells == point_header && kind != SectionKind::richter)
        throw UsageError("--seeds: " + where + ": section points (phi,theta,sheet) only for --section richter");
      header = cells;
      continue;
    }
    if (cells.size() != header.size())
      throw UsageError("--seeds: " + where + ": " + std::to_string(cells.size()) + " values, expected " +
                       std::to_string(header.size()));
    std::vector<double> x;
    for (const auto& c : cells) x.push_back(number_in(c, where));
    SeedState s;
    if (header == point_header) {
      if (x[2] != 1.0 && x[2] != -1.0) throw UsageError("--seeds: " + where + ": sheet must be 1 or -1");
      Vec3 f1, f2;
      section_frame(e, f1, f2);
      s.gamma = std::sin(x[1]) * (std::cos(x[0]) * f1 + std::sin(x[0]) * f2) + std::cos(x[1]) * e;
      if (!section_state(body, e, l, h, s.gamma, static_cast<int>(x[2]), s.Pi))
        throw UsageError("--seeds: " + where + ": no state on the section there at (l, h) (outside the accessible "
                         "region U_l <= h, or a pole theta = 0, pi)");
    } else {
      s.gamma = Vec3(x[0], x[1], x[2]), s.Pi = Vec3(x[3], x[4], x[5]);
      const double H = 0.5 * s.Pi.dot(body.J.inverse() * s.Pi) + body.weight.dot(s.gamma);
      const double tol = 1e-8;
      if (std::abs(s.gamma.norm() - 1.0) > tol || std::abs(s.Pi.dot(s.gamma) - l) > tol * std::max(1.0, std::abs(l)) ||
          std::abs(H - h) > tol * std::max(1.0, std::abs(h)))
        throw UsageError("--seeds: " + where + ": the state is not on the level (|Gamma| = 1, Pi.Gamma = l, H = h "
                         "to 1e-8)");
      s.gamma.normalize();  // the file's digits, made a unit vector (documented in POINCARE.md)
    }
    out.push_back(s);
  }
  if (out.empty()) throw UsageError("--seeds: " + path + " has no rows");
  return out;
}

}  // namespace lgi::experiments
