#include "experiments/cli/scheme_lookup.hpp"

#include <algorithm>
#include <cstddef>

#include "experiments/errors/exit_status.hpp"

namespace lgi::experiments {
namespace {

/// Levenshtein distance (two rows; names are short).
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> previous(b.size() + 1), current(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) previous[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    current[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitute = previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, substitute});
    }
    std::swap(previous, current);
  }
  return previous[b.size()];
}

/// Distance to the whole name, or one more than the distance to its nearest
/// part ("rk4" is close to "quat/rk4" through its stepper part).
std::size_t name_distance(std::string_view typed, std::string_view name) {
  std::size_t best = edit_distance(typed, name);
  std::size_t start = 0;
  while (start <= name.size()) {
    const std::size_t end = std::min(name.find_first_of("/@", start), name.size());
    if (end > start) best = std::min(best, edit_distance(typed, name.substr(start, end - start)) + 1);
    start = end + 1;
  }
  return best;
}

struct Candidate {
  std::size_t distance;
  std::string name;
  bool baseline;
};

}  // namespace

std::vector<const integrators::SchemeInfo*> listed_schemes() {
  std::vector<const integrators::SchemeInfo*> out;
  for (const auto& s : integrators::scheme_registry()) out.push_back(&s);
  for (const auto& s : integrators::cardan_scheme_registry()) out.push_back(&s);
  return out;
}

std::vector<std::string> nearest_scheme_names(std::string_view typed) {
  // A name further than a third of its length (at least 2 edits) is not "near".
  const std::size_t limit = std::max<std::size_t>(2, typed.size() / 3);
  std::vector<Candidate> candidates;
  for (const integrators::SchemeInfo* s : listed_schemes()) {
    const std::size_t d = name_distance(typed, s->name);
    if (d <= limit) candidates.push_back({d, s->name, s->properties.baseline});
  }
  std::stable_sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return a.distance != b.distance ? a.distance < b.distance : a.name.size() < b.name.size();
  });
  std::vector<std::string> out;
  int lie_group = 0, baselines = 0;
  for (const auto& c : candidates) {
    int& count = c.baseline ? baselines : lie_group;
    if (count == 2) continue;
    ++count;
    out.push_back(c.name);
  }
  return out;
}

const integrators::SchemeInfo& scheme_by_name(std::string_view typed, std::string_view flag) {
  if (const integrators::SchemeInfo* s = integrators::find_scheme(typed)) return *s;
  // A scheme of the other state space exists: say so instead of suggesting its own name.
  if (const integrators::SchemeInfo* s = integrators::find_cardan_scheme(typed))
    throw UsageError(std::string(flag) + ": " + s->name + " runs on Cardan scenes only (its state is " +
                     integrators::state_space_name(*s) + "); this command's scenes have state SO(3) x R^3");
  std::string message = std::string(flag) + ": unknown scheme '" + std::string(typed) + "'";
  const std::vector<std::string> near = nearest_scheme_names(typed);
  for (std::size_t i = 0; i < near.size(); ++i)
    message += (i == 0 ? "; did you mean " : i + 1 == near.size() ? " or " : ", ") + near[i];
  message += near.empty() ? " (lgi schemes lists them)" : "? (lgi schemes lists them)";
  throw UsageError(message);
}

}  // namespace lgi::experiments
