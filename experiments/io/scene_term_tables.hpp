#pragma once
// The scene-file tables of the torque terms, one per term of SceneTerms
// (integrators/system/terms/scene_terms.hpp), named by each term's
// scene_table. Each term's keys are read by its read_term_table
// specialisation in scene_term_tables.cpp; that is all a new term needs here.
#include <array>
#include <string_view>
#include <tuple>

#include "experiments/io/scene_toml.hpp"
#include "integrators/system/scene.hpp"

namespace lgi::experiments::scene_toml {

/// Reads the keys of Term's table into its parameters (the scene's [body] is
/// read already: a term may need it).
template <class Term>
typename Term::Parameters read_term_table(const Table& table, const system::Scene& scene);

namespace detail {
template <class List>
struct term_tables;
template <class... Terms>
struct term_tables<system::TermList<Terms...>> {
  static constexpr std::array<std::string_view, sizeof...(Terms)> names{Terms::scene_table...};
  /// The tables first (so that a wrong type is reported before any key)...
  static std::array<Table, sizeof...(Terms)> find(const Table& root) { return {sub_table(root, Terms::scene_table)...}; }
  /// ...then the keys of those present.
  static void read(const std::array<Table, sizeof...(Terms)>& tables, system::Scene& scene) {
    std::size_t i = 0;
    auto read_one = [&]<class Term>() {
      if (tables[i].present()) scene.declared<Term>() = read_term_table<Term>(tables[i], scene);
      ++i;
    };
    (read_one.template operator()<Terms>(), ...);
  }
};
}  // namespace detail

using SceneTermTables = detail::term_tables<system::SceneTerms>;

}  // namespace lgi::experiments::scene_toml
