// Reading a problem file (TOML) into a validated Scene, and describing a Scene in words.
//
// The language is documented key by key in docs/problem-files.md. Every problem the
// reader finds is an InputError whose message is one line:
//   <file>:<line>: <key.path>: <what is wrong>; <what is allowed>
// or, when the value came from the command line, `--set <key.path>` in place of
// <file>:<line>.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "latfrac/scene/scene.h"

namespace latfrac {

// Reads the file at `path`, applies the `--set key.path=value` overrides (each value is
// read as a TOML value, or as a string when it is not one), and validates the result.
// Throws InputError.
Scene read_problem_file(const std::string& path, const std::vector<std::string>& overrides = {});

// The text of the problem file at `path`. A problem file is text of at most
// max_problem_bytes (64 MiB: 100,000 pre-cuts take about 8 MB); a longer one, or a
// device that never ends (/dev/zero), is refused with InputError, as is a file that
// cannot be read. A pipe is read to its end (`latfrac run <(sed ... file.toml)`).
inline constexpr std::size_t max_problem_bytes = std::size_t{64} << 20;
std::string read_problem_text(const std::string& path);

// The same from the text of a problem file; `source_name` names it in messages.
Scene parse_problem(const std::string& text, const std::string& source_name,
                    const std::vector<std::string>& overrides = {});

// The resolved parameters, one per line with their units, defaults included and absent
// sections shown as "off": what `latfrac check` prints and `latfrac run` echoes.
std::string describe(const Scene& scene);

}  // namespace latfrac
