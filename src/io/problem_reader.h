// Checked access to the tables of a parsed problem file: types, ranges, unknown keys.
//
// Every failure throws an InputError of the form
//   <where>: <key.path>: <what is wrong>; <what is allowed>
// where <where> is "<file>:<line>" of the offending node (of its table when a key is
// missing), or "--set <key.path>" when the node came from a command-line override.
#pragma once

#include <toml++/toml.h>

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "latfrac/scene/scene.h"

namespace latfrac::problem {

// The shortest text that reads back as the same double: 250, 1e+11, 0.2.
std::string format_number(double value);

// The closest of `candidates` to `word` (edit distance <= 2, or one a prefix of the
// other), or "" when none is close.
std::string closest_match(std::string_view word, const std::vector<std::string_view>& candidates);

// Where messages point: lines of the problem file, or the --set overrides that created
// nodes without a line.
class Origin {
 public:
  explicit Origin(std::string source_name) : source_name_(std::move(source_name)) {}

  void add_override(std::string key_path) { override_paths_.push_back(std::move(key_path)); }
  std::string where(const toml::node* node, std::string_view key_path) const;
  [[noreturn]] void fail(const toml::node* node, std::string_view key_path, std::string_view wrong,
                         std::string_view allowed) const;

 private:
  std::string source_name_;
  std::vector<std::string> override_paths_;
};

// The allowed values of a number, and its unit for messages.
struct Range {
  static constexpr double infinity = std::numeric_limits<double>::infinity();
  double min = -infinity;
  double max = infinity;
  bool min_open = false;
  bool max_open = false;
  std::string unit;

  bool contains(double value) const;
  std::string describe(std::string_view name) const;  // e.g. "0 <= friction_angle < 90 degrees"
};

inline Range positive(std::string unit = "") { return {0, Range::infinity, true, false, unit}; }
inline Range non_negative(std::string unit = "") {
  return {0, Range::infinity, false, false, unit};
}
inline Range any_finite(std::string unit = "") { return {.unit = std::move(unit)}; }

// One table of the problem file: [lattice], one [[precut]] entry, or the top level.
// Construction rejects keys that are not in `keys`.
class Section {
 public:
  Section(const Origin& origin, const toml::table& table, std::string path, std::string title,
          std::vector<std::string_view> keys);

  const std::string& title() const { return title_; }
  std::string key_path(std::string_view key) const;
  const toml::node* find(std::string_view key) const { return table_->get(key); }
  bool has(std::string_view key) const { return find(key) != nullptr; }

  // Fails at the key's node, or at this table when the key is absent.
  [[noreturn]] void fail(std::string_view key, std::string_view wrong,
                         std::string_view allowed) const;
  [[noreturn]] void fail_missing(std::string_view key, std::string_view allowed) const;

  std::optional<double> number(std::string_view key, const Range& range) const;
  double number(std::string_view key, const Range& range, double fallback) const {
    return number(key, range).value_or(fallback);
  }
  double required_number(std::string_view key, const Range& range) const;
  // An array of numbers; `count` 0 accepts any length. `shape` describes it, e.g. "[x, z]".
  std::optional<std::vector<double>> numbers(std::string_view key, const Range& range,
                                             std::size_t count, std::string_view shape) const;
  std::optional<std::int64_t> integer(std::string_view key, std::int64_t min,
                                      std::int64_t max) const;
  std::optional<bool> boolean(std::string_view key) const;
  std::optional<std::string> string(std::string_view key) const;
  // The index of the value among `names`.
  std::optional<int> choice(std::string_view key, const std::vector<std::string_view>& names) const;
  int required_choice(std::string_view key, const std::vector<std::string_view>& names) const;

  std::optional<Section> section(std::string_view key, std::vector<std::string_view> keys) const;
  Section required_section(std::string_view key, std::vector<std::string_view> keys) const;
  // The entries of an array of tables ([[key]]).
  std::vector<Section> sections(std::string_view key, std::vector<std::string_view> keys) const;

 private:
  double checked_number(const toml::node& node, const std::string& path, const Range& range) const;

  const Origin* origin_;
  const toml::table* table_;
  std::string path_;
  std::string title_;
  std::vector<std::string_view> keys_;
};

// The [lattice] section (problem_lattice.cpp).
LatticeSpec read_lattice(const Section& top);
// The Poisson's ratios the lattice can represent, and why no others (problem_lattice.cpp).
Range poisson_range(const LatticeSpec& lattice);
std::string poisson_limit_reason(const LatticeSpec& lattice);

// The [output] section: snapshots and the picture of the final state (problem_output.cpp).
void read_output(const Section& top, Scene& scene);

// The scene the top level of a problem file describes (problem_sections.cpp).
Scene read_scene(const Origin& origin, const toml::table& root);

}  // namespace latfrac::problem
