// Writing a RunResult to an HDF5 result file and reading it back.
//
// The layout (groups, datasets, attributes, types and units) is documented in
// docs/result-files.md. Files are written atomically: to "<path>.partial" first, renamed to
// <path> only when complete, so an interrupted or failed write never leaves a file at
// <path> that looks complete.
#pragma once

#include <string>

#include "latfrac/fracture/run_result.h"

namespace latfrac {

// Throws Error (naming the HDF5 call and object) if writing fails, after removing the
// partial file; throws Error before creating anything if result's arrays disagree in size.
void write_result_file(const std::string& path, const RunResult& result);

// Throws InputError if path is missing, is not HDF5, is not a latfrac result, or lacks a
// dataset or attribute, or holds one of the wrong shape; Error if an HDF5 call fails.
RunResult read_result_file(const std::string& path);

}  // namespace latfrac
