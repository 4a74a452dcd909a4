// The convergence study: a scene run event-driven (the reference) and fixed-step at a list
// of increments, each run compared with the reference (docs/convergence-study.md).
//
// Every run goes to lambda = loading.total and keeps one snapshot, at total. A row holds
// the run's cost (wall time, solves) and two errors against the reference:
//   first-break error  |lambda_1 - lambda_1,ref| / |lambda_1,ref|, lambda_1 the lambda of
//                      the first break that is not a pre-cut;
//   broken-set difference  |B triangle B_ref| / |B_ref|, B the bonds broken in the final
//                      snapshot, pre-cut bonds excluded. When the reference breaks nothing
//                      the denominator is taken as 1: the difference is then the number of
//                      bonds the run broke (0 when it broke none either).
// The fixed-step method converges to the event-driven one as ds -> 0 (docs/model.md,
// section 5), so both errors should fall with ds while the cost rises.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "latfrac/fracture/run_result.h"
#include "latfrac/scene/scene.h"

namespace latfrac {

// ok: the run finished; not_available: this version refused it (InputError, e.g. a solver
// not yet written); failed: it started and stopped with an error.
enum class RunStatus { ok, not_available, failed };
const char* to_string(RunStatus status);

// One run of the study: one row of study.csv and study.md.
struct StudyRow {
  std::string method;               // "event", "fixed" or "fixed+relaxation"
  bool reference = false;           // the run the others are compared with
  std::optional<double> increment;  // ds; empty for "event"
  RunStatus status = RunStatus::ok;
  std::string note;                             // why the run is not available or failed
  std::int64_t breaks = 0;                      // pre-cut bonds excluded
  std::optional<double> first_break_lambda;     // empty when the run breaks nothing
  std::optional<double> first_break_error;      // empty when either run breaks nothing
  std::optional<double> broken_set_difference;  // fraction of the reference's broken set
  std::optional<double> fault_angle;            // alpha of the largest non-diffuse fault, degrees
  double wall_seconds = 0;
  std::int64_t solves = 0;
};

struct StudyResult {
  std::string scene_name;
  std::string command_line;
  std::string date;            // ISO 8601, UTC
  std::vector<StudyRow> rows;  // the reference first, then the runs in the order given
};

struct StudyOptions {
  std::vector<double> increments;  // ds of the fixed-step runs, each > 0
  bool relaxation = false;         // also each increment with solver.method = relaxation
  // When set, the reference is a fixed-step run at this increment instead of the
  // event-driven run (for tests, and for scenes the event-driven method cannot run).
  std::optional<double> reference_increment;
  bool run_progress = false;  // each run's own progress line on stderr
  std::string command_line;   // recorded in study.md and in each run's provenance
  // Called once a run has finished (or was found not available), reference included.
  std::function<void(const StudyRow&)> on_row;
};

// Parses "1e-2,3e-3,1e-3": comma-separated positive finite numbers, no repeats. Throws
// InputError naming the offending item.
std::vector<double> parse_increments(const std::string& list);

// An increment as short as it reads back exactly: 1e-3, 2.5e-4, 5e-1 (for labels).
std::string increment_text(double increment);

// The bonds broken in the last snapshot (bond_intact == 0), pre-cut bonds excluded; sorted.
std::vector<std::int64_t> final_broken_set(const RunResult& result);
// The lambda of the first break that is not a pre-cut.
std::optional<double> first_break_lambda(const RunResult& result);
// |run triangle reference| / |reference| (1 in place of |reference| when it is empty);
// both sets sorted and without repeats.
double broken_set_difference(const std::vector<std::int64_t>& run,
                             const std::vector<std::int64_t>& reference);

// Runs the reference and every requested run. An error in the reference propagates; a run
// refused with InputError becomes a row that is not available, one that throws another
// error a row that failed, and the study goes on.
StudyResult run_study(const Scene& scene, const StudyOptions& options);

// The one-line progress report of a finished run: "fixed ds=1e-3: 123 breaks, 4.5 s".
std::string progress_line(const StudyRow& row);

// The two sentences of interpretation in study.md: the largest increment whose broken
// set matches the reference's (exactly, or else within 1 %), and its cost.
std::vector<std::string> study_interpretation(const StudyResult& study);

std::string study_csv(const StudyResult& study);
std::string study_markdown(const StudyResult& study);
// study.png: error against wall time, log-log (src/study/study_plot.cpp).
void write_study_plot(const StudyResult& study, const std::string& path);

// Writes study.csv, study.md and study.png into out_dir (created if missing), each under
// a temporary name renamed when complete.
void write_study(const StudyResult& study, const std::string& out_dir);

}  // namespace latfrac
