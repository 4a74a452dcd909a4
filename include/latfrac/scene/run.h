// Running a scene: from a Scene to a RunResult (the continuation in lambda, snapshots,
// provenance), and the one-screen summary of a result.
#pragma once

#include "latfrac/solvers/linear_backend.h"

#include <string>
#include <vector>

#include "latfrac/fracture/run_control.h"
#include "latfrac/fracture/run_result.h"
#include "latfrac/scene/scene.h"

namespace latfrac {

// A run to continue: the results so far (an incomplete result file) and its checkpoint.
struct ResumePoint {
  RunResult result;
  RunCheckpoint checkpoint;
};

struct RunOptions {
  std::string command_line;  // recorded in the provenance
  bool progress = true;      // the progress line on stderr
  // Between events, asked whether to save a checkpoint and whether to stop; also given
  // the results at the start (lattice and provenance, before anything is computed).
  RunControl* control = nullptr;
  const ResumePoint* resume = nullptr;  // continue this run instead of starting afresh
  // When given, receives what the linear backend did (benchmarks; the petsc backend's
  // factorizations and CG iterations), also when the run stops on request.
  LinearBackend::Statistics* backend_statistics = nullptr;
};

// The effects a scene names that this version cannot simulate yet (empty: it can run).
std::vector<std::string> unsupported_effects(const Scene& scene);

// Runs a scene along lambda from 0 to loading.total: a fracture run (fracture_run.h) when
// it has a [strength] section, equilibrium at each snapshot otherwise. Stores a snapshot
// at each requested lambda (the final state when none are requested). Throws InputError
// for a scene with unsupported effects, Error when a solve fails. A run stopped on request
// (options.control) returns what it has, with summary.complete false; a resumed one
// returns the whole run's results, the resumed part's included, with the provenance of
// the run's start. Throws InputError when a checkpoint does not fit the scene's model.
RunResult run_scene(const Scene& scene, const RunOptions& options);

// Throws InputError naming `what` (the key or option that gave the increment) when
// |total| / increment exceeds max_fixed_steps (schedule.h).
void check_step_count(double total, double increment, const std::string& what);

// The current time in ISO 8601 (UTC), as provenance records it.
std::string utc_timestamp();

// This build's version and commit, as provenance records them (one definition, so that
// a resume compares with exactly what a run writes).
std::string code_version();
std::string code_commit();

// The summary printed at the end of a run and by `latfrac analyze`.
std::string summary_text(const RunResult& result);

}  // namespace latfrac
