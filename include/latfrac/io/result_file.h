// Writing a RunResult to an HDF5 result file and reading it back.
//
// The layout (groups, datasets, attributes, types and units) is documented in
// docs/result-files.md. Files are written atomically: to "<path>.partial" first, renamed to
// <path> only when complete, so an interrupted or failed write never leaves a file at
// <path> that looks complete.
#pragma once

#include <string>

#include "latfrac/fracture/run_control.h"
#include "latfrac/fracture/run_result.h"

namespace latfrac {

// Throws Error (naming the HDF5 call and object) if writing fails, after removing the
// partial file; throws Error before creating anything if result's arrays disagree in size.
// With a checkpoint, the file is an incomplete one that a run can continue from (its
// /checkpoint group, docs/restart.md), synced to disk before it is renamed into place.
void write_result_file(const std::string& path, const RunResult& result,
                       const RunCheckpoint* checkpoint = nullptr);

// Throws InputError if path is missing, is not HDF5, is not a latfrac result, or lacks a
// dataset or attribute, or holds one of the wrong shape; Error if an HDF5 call fails.
RunResult read_result_file(const std::string& path);

// Throws Error when the result holds a value that is not a finite number (positions,
// events, fragments, snapshots): the last guard of "no NaN in the output", which
// write_result_file applies and `latfrac study` applies to each run it tabulates.
void check_result_finite(const RunResult& result);

// The checkpoint of an incomplete result file. Throws InputError when the run finished
// (nothing to resume) or the file has no usable /checkpoint group.
RunCheckpoint read_checkpoint(const std::string& path);

}  // namespace latfrac
