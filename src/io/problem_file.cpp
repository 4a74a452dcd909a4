// Reading a problem file: its text, the TOML parse, and the --set overrides applied to it.
#include "latfrac/io/problem_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <regex>
#include <string>
#include <string_view>

#include "latfrac/base/error.h"
#include "problem_reader.h"

namespace latfrac {
namespace {

// The line of the first byte that is not UTF-8 text, or 0 when the text is clean.
std::size_t first_invalid_utf8_line(const std::string& text) {
  std::size_t line = 1;
  for (std::size_t k = 0; k < text.size();) {
    const auto byte = static_cast<unsigned char>(text[k]);
    const int length = byte < 0x80           ? 1
                       : (byte >> 5) == 0x6  ? 2
                       : (byte >> 4) == 0xE  ? 3
                       : (byte >> 3) == 0x1E ? 4
                                             : 0;
    if (length == 0 || k + length > text.size()) return line;
    for (int c = 1; c < length; ++c) {
      if ((static_cast<unsigned char>(text[k + c]) >> 6) != 0x2) return line;
    }
    if ((byte < 0x20 && byte != '\n' && byte != '\r' && byte != '\t') || byte == 0x7F) return line;
    if (byte == '\n') ++line;
    k += length;
  }
  return 0;
}

// The line where a bracket opened before `error_line` is still open, or 0. Strings and
// comments are skipped; a table header ([name] at the start of a line) does not count.
std::size_t unclosed_bracket_line(const std::string& text, std::size_t error_line) {
  std::size_t line = 1, opened_on = 0;
  int depth = 0;
  bool at_line_start = true;
  char quote = 0;
  for (std::size_t k = 0; k < text.size() && line < error_line; ++k) {
    const char c = text[k];
    if (c == '\n') {
      ++line;
      at_line_start = true;
      quote = 0;
      continue;
    }
    if (quote) {
      if (c == quote && text[k - 1] != '\\') quote = 0;
      continue;
    }
    if (c == '#') {
      while (k + 1 < text.size() && text[k + 1] != '\n') ++k;
      continue;
    }
    if (c == '"' || c == '\'') quote = c;
    if (c == '[' && !(at_line_start && depth == 0)) {
      if (depth++ == 0) opened_on = line;
    } else if (c == '[' && at_line_start) {
      while (k + 1 < text.size() && text[k + 1] != '\n') ++k;  // a table header
      continue;
    } else if (c == ']' && depth > 0) {
      --depth;
    }
    if (c != ' ' && c != '\t') at_line_start = false;
  }
  return depth > 0 ? opened_on : 0;
}

toml::table parse_toml(const std::string& text, const std::string& source_name) {
  if (const std::size_t line = first_invalid_utf8_line(text)) {
    throw InputError(source_name + ":" + std::to_string(line) +
                     ": malformed TOML: this line holds bytes that are not valid utf-8 text (is "
                     "this a problem file?)");
  }
  try {
    return toml::parse(text, std::string_view(source_name));
  } catch (const toml::parse_error& error) {
    std::size_t line = error.source().begin.line;
    std::string description(error.description());
    if (description.find("parsing array") != std::string::npos) {
      if (const std::size_t opened = unclosed_bracket_line(text, line)) {
        line = opened;
        description = "an array opened on this line is not closed with ']'";
      }
    } else if (description.find("parsing string") != std::string::npos) {
      description =
          "a string on this line is unclosed: it needs its closing quote (" + description + ")";
    }
    throw InputError(source_name + ":" + std::to_string(line) + ": malformed TOML: " + description +
                     "; see https://toml.io for the syntax");
  }
}

std::string trim(std::string_view text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string_view::npos) return "";
  return std::string(text.substr(first, text.find_last_not_of(" \t") - first + 1));
}

// Sets table[key] to the override's value read as TOML (500, true, [1, 2], "x"), or as a
// bare string (tensile). Its nodes carry "--set <key.path>" as their source, so that
// messages point at the override.
void set_value(toml::table& table, const std::string& key, const std::string& value,
               const std::string& where) {
  try {
    toml::table parsed = toml::parse("value = " + value, std::string_view(where));
    if (parsed.size() == 1 && parsed.contains("value")) {
      table.insert_or_assign(key, std::move(*parsed.get("value")));
      return;
    }
  } catch (const toml::parse_error& error) {
    // A number TOML cannot hold (an integer beyond 64 bits) is not a bare string.
    static const std::regex number(R"([+-]?[0-9][0-9_]*(\.[0-9_]+)?([eE][+-]?[0-9_]+)?)");
    if (std::regex_match(value, number))
      throw InputError(where + ": " + value + " is not a number TOML can hold (" +
                       std::string(error.description()) + ")");
  }
  table.insert_or_assign(key, value);
}

void apply_override(toml::table& root, const std::string& text, problem::Origin& origin) {
  const std::string example = "expected --set key.path=value, e.g. --set lattice.spacing=500";
  const std::size_t equals = text.find('=');
  if (equals == std::string::npos) {
    throw InputError("--set " + text + ": malformed override, it has no '='; " + example);
  }
  const std::string path = trim(std::string_view(text).substr(0, equals));
  const std::string where = "--set " + path;
  std::vector<std::string> keys;
  for (std::size_t start = 0;;) {
    const std::size_t dot = path.find('.', start);
    keys.push_back(path.substr(start, dot - start));
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  for (const std::string& key : keys) {
    const bool bare = !key.empty() && key.find_first_not_of(
                                          "abcdefghijklmnopqrstuvwxyz"
                                          "ABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                          "0123456789_-") == std::string::npos;
    if (!bare) {
      throw InputError(where + ": malformed override, '" + path + "' is not a key path; " +
                       example);
    }
  }

  toml::table* table = &root;
  std::string prefix;
  for (std::size_t i = 0; i + 1 < keys.size(); ++i) {
    prefix += (i > 0 ? "." : "") + keys[i];
    toml::node* child = table->get(keys[i]);
    const bool numeric = keys[i].find_first_not_of("0123456789") == std::string::npos;
    if (numeric || (child != nullptr && child->is_array())) {
      throw InputError(where + ": " + prefix +
                       ": entries of an array of tables cannot be set from the command line; "
                       "edit the problem file, or replace the whole array");
    }
    if (child == nullptr) child = &table->insert(keys[i], toml::table{}).first->second;
    if (!child->is_table()) {
      throw InputError(where + ": " + prefix + ": is a value, not a section; " + "allowed: --set " +
                       prefix + "=value");
    }
    table = child->as_table();
  }
  set_value(*table, keys.back(), trim(std::string_view(text).substr(equals + 1)), where);
  origin.add_override(path);
}

}  // namespace

std::string read_problem_text(const std::string& path) {
  const auto fail = [&] {
    throw InputError("cannot read problem file '" + path + "': " + std::strerror(errno));
  };
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"),
                                                             &std::fclose);
  if (!file) fail();
  std::string text;
  char buffer[65536];
  std::size_t count = 0;
  while ((count = std::fread(buffer, 1, sizeof buffer, file.get())) > 0) {
    if (text.size() + count > max_problem_bytes)
      throw InputError("problem file '" + path + "' is longer than " +
                       std::to_string(max_problem_bytes >> 20) +
                       " MiB (or a device that never ends); allowed: a TOML text file of at "
                       "most that size");
    text.append(buffer, count);
  }
  if (std::ferror(file.get())) fail();
  return text;
}

Scene parse_problem(const std::string& text, const std::string& source_name,
                    const std::vector<std::string>& overrides) {
  toml::table root = parse_toml(text, source_name);
  problem::Origin origin(source_name);
  for (const std::string& override_text : overrides) apply_override(root, override_text, origin);
  Scene scene = problem::read_scene(origin, root);
  scene.source_path = source_name;
  scene.source_text = text;
  return scene;
}

Scene read_problem_file(const std::string& path, const std::vector<std::string>& overrides) {
  return parse_problem(read_problem_text(path), path, overrides);
}

}  // namespace latfrac
