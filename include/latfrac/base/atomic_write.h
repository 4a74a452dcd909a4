// Writing a file under a temporary name and renaming it only once it is complete.
#pragma once

#include <filesystem>
#include <string>
#include <system_error>

#include "latfrac/base/error.h"

namespace latfrac {

inline std::string partial_path(const std::string& path) { return path + ".partial"; }

// Makes `directory` and its missing parents (nothing when it is empty or exists); throws
// Error naming it when it cannot be made (a regular file in the way, no permission).
inline void make_directory(const std::filesystem::path& directory) {
  if (directory.empty()) return;
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error)
    throw Error("cannot create output directory '" + directory.string() + "': " + error.message());
}

// Calls write(partial_path(path)), then renames the partial file to path. If write throws
// or the rename fails, the partial file is removed and the exception propagates, so a
// reader never sees a file at path that is not complete.
template <class WriteFunction>
void write_atomically(const std::string& path, WriteFunction write) {
  const std::string partial = partial_path(path);
  try {
    write(partial);
    std::error_code error;
    std::filesystem::rename(partial, path, error);
    if (error) {
      throw Error("cannot rename '" + partial + "' to '" + path + "': " + error.message());
    }
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(partial, ignored);
    throw;
  }
}

}  // namespace latfrac
