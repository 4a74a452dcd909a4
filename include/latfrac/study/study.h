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
// and the angles of the faults that matter (docs/fault-analysis.md, "Roles"): the graben's
// two faults and the fault through or from the tip of the pre-cut, each with the angle
// between it and the reference's. The fixed-step method converges to the event-driven one
// as ds -> 0 (docs/model.md, section 5), so the errors should fall with ds while the cost
// rises.
#pragma once

#include <array>
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

// A fault the study follows from run to run.
struct TrackedFault {
  double alpha_deg = 0;            // angle to the vertical (sigma1), degrees
  int side = 0;                    // the way it descends: +1 towards +x, -1 towards -x, 0 neither
  std::array<double, 3> normal{};  // unit normal of its fitted line or plane
};

// The faults that matter in a run's final snapshot; each empty when the run has none.
struct FaultAngles {
  std::optional<TrackedFault> graben_left;   // the graben's fault that descends towards +x
  std::optional<TrackedFault> graben_right;  // the graben's fault that descends towards -x
  std::optional<TrackedFault> precut;        // the fault through or from the pre-cut's tip
};

// The angle between two runs' faults, in each row against the reference's; each empty when
// either run lacks that fault.
struct AngleDifferences {
  std::optional<double> graben_left, graben_right, precut;  // degrees
};

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
  FaultAngles faults;                           // the graben's and the pre-cut fault's angles
  AngleDifferences angle_differences;           // against the reference's faults
  double wall_seconds = 0;
  std::int64_t solves = 0;
};

struct StudyResult {
  std::string scene_name;
  std::string command_line;
  std::string date;            // ISO 8601, UTC
  std::vector<StudyRow> rows;  // the reference first, then the runs in the order given
  // A stop was asked for (SIGINT, SIGTERM): `rows` holds the runs that finished before it;
  // the run it interrupted is not among them and the later ones did not start.
  bool stopped = false;
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

// The faults that matter in the run's last snapshot (analyze_faults with its defaults).
FaultAngles fault_angles(const RunResult& run);
// The angle between two faults' lines (2-D) or planes (3-D), degrees, 0 .. 90: for two
// lines descending to the same side |alpha_a - alpha_b|, to opposite sides alpha_a + alpha_b
// (or 180 minus that).
double angle_between(const TrackedFault& a, const TrackedFault& b);
// Each of the run's faults against the reference's, where both have it.
AngleDifferences angle_differences(const FaultAngles& run, const FaultAngles& reference);

// What every run is compared with.
struct ReferenceFacts {
  std::optional<double> first_break;  // lambda of the reference's first break (no pre-cut)
  std::vector<std::int64_t> broken;   // its final broken set, sorted
  FaultAngles faults;
};
ReferenceFacts reference_facts(const RunResult& reference);
// The numbers of a row from its finished run, compared with the reference.
void fill_from_run(StudyRow& row, const RunResult& run, const ReferenceFacts& reference);

// Runs the reference and every requested run. An error in the reference propagates; a run
// refused with InputError becomes a row that is not available, one that throws another
// error a row that failed, and the study goes on.
StudyResult run_study(const Scene& scene, const StudyOptions& options);

// The one-line progress report of a finished run: "fixed ds=1e-3: 123 breaks, 4.5 s".
std::string progress_line(const StudyRow& row);

// The three sentences of interpretation in study.md: the largest increment whose broken
// set matches the reference's (exactly, or else within 1 %), its cost, and the largest
// increment whose fault angles all lie within kAngleMatchDeg of the reference's.
std::vector<std::string> study_interpretation(const StudyResult& study);
// Fault angles this close (degrees) count as the same: the analysis recovers a straight
// lattice fault's dip within about 0.5 deg (docs/fault-analysis.md, "Limitations").
inline constexpr double kAngleMatchDeg = 1.0;
// The third sentence: the angles' reading.
std::string angle_interpretation(const StudyResult& study);

std::string study_csv(const StudyResult& study);
std::string study_markdown(const StudyResult& study);
// study.png: error against wall time and wall time against increment, log-log
// (src/study/study_plot.cpp).
void write_study_plot(const StudyResult& study, const std::string& path);

// Writes study.csv, study.md and study.png into out_dir (created if missing), each under
// a temporary name renamed when complete.
void write_study(const StudyResult& study, const std::string& out_dir);

}  // namespace latfrac
