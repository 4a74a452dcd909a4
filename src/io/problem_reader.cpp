// Checked access to the tables of a parsed problem file, and the messages it gives.
#include "problem_reader.h"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "latfrac/base/error.h"

namespace latfrac::problem {
namespace {

std::string_view type_name(toml::node_type type) {
  switch (type) {
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a floating-point number";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::table:
      return "a table";
    case toml::node_type::date:
      return "a date";
    case toml::node_type::time:
      return "a time";
    case toml::node_type::date_time:
      return "a date-time";
    case toml::node_type::none:
      break;
  }
  return "nothing";
}

std::string got(const toml::node& node) { return "got " + std::string(type_name(node.type())); }

std::string join(const std::vector<std::string_view>& words, std::string_view quote = "") {
  std::string text;
  for (std::size_t i = 0; i < words.size(); ++i) {
    if (i > 0) text += ", ";
    text.append(quote).append(words[i]).append(quote);
  }
  return text;
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string did_you_mean(std::string_view word, const std::vector<std::string_view>& candidates,
                         std::string_view before = "'", std::string_view after = "'") {
  const std::string match = closest_match(word, candidates);
  if (match.empty()) return "";
  return " (did you mean " + std::string(before) + match + std::string(after) + "?)";
}

std::string describe_choice(const std::vector<std::string_view>& names) {
  return "allowed: " + join(names, "\"");
}

}  // namespace

std::string format_number(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::string closest_match(std::string_view word, const std::vector<std::string_view>& candidates) {
  std::string best;
  std::size_t best_distance = 3;
  for (const std::string_view candidate : candidates) {
    const std::size_t distance = edit_distance(word, candidate);
    if (distance < best_distance) {
      best_distance = distance;
      best = candidate;
    }
  }
  if (!best.empty() || word.size() < 2) return best;
  for (const std::string_view candidate : candidates) {
    if (candidate.starts_with(word) || word.starts_with(candidate)) return std::string(candidate);
  }
  return "";
}

std::string Origin::where(const toml::node* node, std::string_view key_path) const {
  if (node != nullptr) {
    const toml::source_region& source = node->source();
    if (source.path && source.path->starts_with("--set ")) return *source.path;
    if (source.begin.line > 0) return source_name_ + ":" + std::to_string(source.begin.line);
  }
  // A node the overrides created: name the override that shares most of its key path.
  std::string prefix(key_path);
  while (!prefix.empty()) {
    // The override of exactly this path first: `--set lattice.spacing=3000 --set lattice=`
    // named the first of the two for a wrong `lattice`.
    for (const std::string& set : override_paths_)
      if (set == prefix) return "--set " + set;
    for (const std::string& set : override_paths_) {
      if (set.starts_with(prefix + ".")) return "--set " + set;
    }
    const std::size_t parent_end = prefix.find_last_of(".[");
    prefix.erase(parent_end == std::string::npos ? 0 : parent_end);
  }
  return source_name_ + ":1";
}

void Origin::fail(const toml::node* node, std::string_view key_path, std::string_view wrong,
                  std::string_view allowed) const {
  std::string message = where(node, key_path) + ": ";
  if (!key_path.empty()) message.append(key_path).append(": ");
  message.append(wrong).append("; ").append(allowed);
  throw InputError(message);
}

bool Range::contains(double value) const {
  const bool above_min = min_open ? value > min : value >= min;
  const bool below_max = max_open ? value < max : value <= max;
  return above_min && below_max;
}

std::string Range::describe(std::string_view name) const {
  std::string text;
  if (std::isfinite(min) && std::isfinite(max)) {
    text = format_number(min) + (min_open ? " < " : " <= ") + std::string(name) +
           (max_open ? " < " : " <= ") + format_number(max);
  } else if (std::isfinite(min)) {
    text = std::string(name) + (min_open ? " > " : " >= ") + format_number(min);
  } else if (std::isfinite(max)) {
    text = std::string(name) + (max_open ? " < " : " <= ") + format_number(max);
  } else {
    text = "a finite number";
  }
  if (!unit.empty()) text += " (" + unit + ")";
  return text;
}

Section::Section(const Origin& origin, const toml::table& table, std::string path,
                 std::string title, std::vector<std::string_view> keys)
    : origin_(&origin),
      table_(&table),
      path_(std::move(path)),
      title_(std::move(title)),
      keys_(std::move(keys)) {
  for (const auto& [key, node] : table) {
    if (std::find(keys_.begin(), keys_.end(), key.str()) != keys_.end()) continue;
    const bool top_level = path_.empty();
    if (top_level && (node.is_table() || node.is_array_of_tables())) {
      origin_->fail(&node, key.str(),
                    "unknown section [" + std::string(key.str()) + "]" +
                        did_you_mean(key.str(), keys_, "[", "]"),
                    "allowed at the top level: " + join(keys_));
    }
    origin_->fail(&node, key_path(key.str()), "unknown key" + did_you_mean(key.str(), keys_),
                  "allowed in " + title_ + ": " + join(keys_));
  }
}

std::string Section::key_path(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

void Section::fail(std::string_view key, std::string_view wrong, std::string_view allowed) const {
  const toml::node* node = find(key);
  origin_->fail(node != nullptr ? node : table_, key_path(key), wrong, allowed);
}

void Section::fail_missing(std::string_view key, std::string_view allowed) const {
  origin_->fail(table_, key_path(key), "missing required key", allowed);
}

double Section::checked_number(const toml::node& node, const std::string& path,
                               const Range& range) const {
  std::string_view name = std::string_view(path).substr(path.find_last_of('.') + 1);
  name = name.substr(0, name.find('['));
  double value = 0;
  if (const auto* integer = node.as_integer()) {
    value = static_cast<double>(integer->get());
  } else if (const auto* floating = node.as_floating_point()) {
    value = floating->get();
    if (!std::isfinite(value)) {
      origin_->fail(&node, path, "must be finite, got " + format_number(value),
                    "allowed: " + range.describe(name));
    }
  } else {
    origin_->fail(&node, path, "expected a number, " + got(node),
                  "allowed: " + range.describe(name));
  }
  if (!range.contains(value)) {
    origin_->fail(&node, path, format_number(value) + " is out of range",
                  "allowed: " + range.describe(name));
  }
  return value;
}

std::optional<double> Section::number(std::string_view key, const Range& range) const {
  const toml::node* node = find(key);
  if (node == nullptr) return std::nullopt;
  return checked_number(*node, key_path(key), range);
}

double Section::required_number(std::string_view key, const Range& range) const {
  if (!has(key)) fail_missing(key, "allowed: " + range.describe(key));
  return *number(key, range);
}

std::optional<std::vector<double>> Section::numbers(std::string_view key, const Range& range,
                                                    std::size_t count,
                                                    std::string_view shape) const {
  const toml::node* node = find(key);
  if (node == nullptr) return std::nullopt;
  const std::string each = "each " + range.describe("value");
  const std::string expected =
      count > 0 ? "an array of " + std::to_string(count) + " numbers " + std::string(shape)
                : "an array of numbers " + std::string(shape);
  const toml::array* array = node->as_array();
  if (array == nullptr) fail(key, "expected " + expected + ", " + got(*node), "allowed: " + each);
  if (count > 0 && array->size() != count) {
    fail(key, "expected " + expected + ", got " + std::to_string(array->size()) + " numbers",
         "allowed: " + std::string(shape) + ", " + each);
  }
  std::vector<double> values;
  for (std::size_t i = 0; i < array->size(); ++i) {
    const std::string element = key_path(key) + "[" + std::to_string(i) + "]";
    values.push_back(checked_number(*array->get(i), element, range));
  }
  return values;
}

std::optional<std::int64_t> Section::integer(std::string_view key, std::int64_t min,
                                             std::int64_t max) const {
  const toml::node* node = find(key);
  if (node == nullptr) return std::nullopt;
  const std::string allowed =
      "allowed: an integer " + (max >= std::numeric_limits<int>::max()
                                    ? ">= " + std::to_string(min)
                                    : "from " + std::to_string(min) + " to " + std::to_string(max));
  const auto* value = node->as_integer();
  if (value == nullptr) fail(key, "expected an integer, " + got(*node), allowed);
  if (value->get() < min || value->get() > max) {
    fail(key, std::to_string(value->get()) + " is out of range", allowed);
  }
  return value->get();
}

std::optional<bool> Section::boolean(std::string_view key) const {
  const toml::node* node = find(key);
  if (node == nullptr) return std::nullopt;
  const auto* value = node->as_boolean();
  if (value == nullptr) fail(key, "expected a boolean, " + got(*node), "allowed: true or false");
  return value->get();
}

std::optional<std::string> Section::string(std::string_view key) const {
  const toml::node* node = find(key);
  if (node == nullptr) return std::nullopt;
  const auto* value = node->as_string();
  if (value == nullptr) fail(key, "expected a string, " + got(*node), "allowed: a quoted string");
  return value->get();
}

std::optional<int> Section::choice(std::string_view key,
                                   const std::vector<std::string_view>& names) const {
  const toml::node* node = find(key);
  if (node == nullptr) return std::nullopt;
  const auto* value = node->as_string();
  if (value == nullptr) fail(key, "expected a string, " + got(*node), describe_choice(names));
  const auto found = std::find(names.begin(), names.end(), value->get());
  if (found == names.end()) {
    fail(key,
         "\"" + value->get() + "\" is not allowed" + did_you_mean(value->get(), names, "\"", "\""),
         describe_choice(names));
  }
  return static_cast<int>(found - names.begin());
}

int Section::required_choice(std::string_view key,
                             const std::vector<std::string_view>& names) const {
  if (!has(key)) fail_missing(key, describe_choice(names));
  return *choice(key, names);
}

std::optional<Section> Section::section(std::string_view key,
                                        std::vector<std::string_view> keys) const {
  const toml::node* node = find(key);
  if (node == nullptr) return std::nullopt;
  const std::string title = std::string("[").append(key_path(key)).append("]");
  if (!node->is_table()) {
    fail(key, "expected a table " + title + ", " + got(*node),
         "allowed: a section " + title + " with keys " + join(keys));
  }
  return Section(*origin_, *node->as_table(), key_path(key), title, std::move(keys));
}

Section Section::required_section(std::string_view key, std::vector<std::string_view> keys) const {
  if (!has(key)) {
    origin_->fail(table_, key_path(key), "missing required section [" + key_path(key) + "]",
                  "add it, with keys " + join(keys));
  }
  return *section(key, std::move(keys));
}

std::vector<Section> Section::sections(std::string_view key,
                                       std::vector<std::string_view> keys) const {
  const toml::node* node = find(key);
  if (node == nullptr) return {};
  const std::string title = "[[" + key_path(key) + "]]";
  if (node->is_array() && node->as_array()->empty()) return {};
  if (!node->is_array_of_tables()) {
    fail(key, "expected an array of tables " + title + ", " + got(*node),
         "allowed: one " + title + " section per entry, with keys " + join(keys));
  }
  std::vector<Section> entries;
  const toml::array& array = *node->as_array();
  for (std::size_t i = 0; i < array.size(); ++i) {
    entries.emplace_back(*origin_, *array.get(i)->as_table(),
                         key_path(key) + "[" + std::to_string(i) + "]", title, keys);
  }
  return entries;
}

}  // namespace latfrac::problem
