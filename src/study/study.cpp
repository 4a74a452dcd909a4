// The convergence study: the runs and their comparison with the reference.
#include "latfrac/study/study.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <set>
#include <sstream>

#include "latfrac/base/error.h"
#include "latfrac/base/stop_signal.h"
#include "latfrac/fracture/run_control.h"
#include "latfrac/io/result_file.h"
#include "latfrac/scene/run.h"
#include "study_format.h"

namespace latfrac {
namespace {

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

// The scene of one run: the study's scene with its stepping and solver replaced, and a
// single snapshot at loading.total (the state the broken sets are compared in).
Scene run_variant(const Scene& scene, SteppingMethod method, double increment,
                  EquilibriumMethod solver) {
  Scene variant = scene;
  variant.stepping = {method,
                      method == SteppingMethod::fixed ? increment : scene.stepping.increment};
  variant.solver.method = solver;
  variant.output.snapshots = {scene.loading.total};
  variant.output.picture = false;
  return variant;
}

// A run of the study stops between its events when a stop was asked for, and saves
// nothing: the study writes its files whole or not at all.
class StopOnRequest final : public RunControl {
 public:
  bool stop_requested() const override { return latfrac::stop_requested(); }
  bool checkpoint_due() override { return false; }
  void save(RunResult&, RunCheckpoint&) override {}
};

}  // namespace

const char* to_string(RunStatus status) {
  switch (status) {
    case RunStatus::ok:
      return "ok";
    case RunStatus::not_available:
      return "not available";
    case RunStatus::failed:
      return "failed";
  }
  return "?";
}

std::string increment_text(double increment) {
  char text[40];
  for (int digits = 0; digits < 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*e", digits, increment);
    if (std::strtod(text, nullptr) == increment) break;
  }
  std::string mantissa = text, exponent;
  if (const auto e = mantissa.find('e'); e != std::string::npos) {
    exponent = mantissa.substr(e + 1);
    mantissa.erase(e);
  }
  const bool negative = !exponent.empty() && exponent[0] == '-';
  exponent = exponent.substr(exponent.find_first_not_of("+-0") == std::string::npos
                                 ? exponent.size()
                                 : exponent.find_first_not_of("+-0"));
  if (exponent.empty()) return mantissa;
  return mantissa + "e" + (negative ? "-" : "") + exponent;
}

std::vector<double> parse_increments(const std::string& list) {
  const std::string allowed =
      "allowed: a comma-separated list of increments > 0, e.g. 1e-2,3e-3,1e-3";
  if (trimmed(list).empty()) throw InputError("--increments: the list is empty; " + allowed);
  std::vector<double> increments;
  std::stringstream items(list);
  std::string item;
  std::size_t position = 0;
  while (std::getline(items, item, ',')) {
    ++position;
    const std::string text = trimmed(item);
    if (text.empty())
      throw InputError("--increments: item " + std::to_string(position) + " is empty; " + allowed);
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (end != text.c_str() + text.size())
      throw InputError("--increments: '" + text + "' is not a number; " + allowed);
    if (!std::isfinite(value) || value <= 0)
      throw InputError("--increments: '" + text + "' is not a positive finite number; " + allowed);
    // A strain step above 1 is one step over any loading a small-strain scene has (and
    // 1e308 broke the plot's log axis).
    if (value > 1)
      throw InputError("--increments: '" + text + "' is a strain step above 1; " + allowed +
                       " and at most 1");
    if (std::find(increments.begin(), increments.end(), value) != increments.end())
      throw InputError("--increments: '" + text + "' is listed twice; " + allowed);
    increments.push_back(value);
  }
  if (trimmed(list).back() == ',')
    throw InputError("--increments: item " + std::to_string(position + 1) + " is empty; " +
                     allowed);
  return increments;
}

std::vector<std::int64_t> final_broken_set(const RunResult& result) {
  std::vector<std::int64_t> broken;
  if (result.snapshots.empty()) return broken;
  std::set<std::int64_t> precut;
  for (const BreakEvent& e : result.events)
    if (e.mode == BreakMode::precut) precut.insert(e.bond);
  const std::vector<std::uint8_t>& intact = result.snapshots.back().bond_intact;
  for (std::size_t bond = 0; bond < intact.size(); ++bond)
    if (!intact[bond] && !precut.count(static_cast<std::int64_t>(bond))) broken.push_back(bond);
  return broken;
}

std::optional<double> first_break_lambda(const RunResult& result) {
  for (const BreakEvent& e : result.events)
    if (e.mode != BreakMode::precut) return e.lambda;
  return std::nullopt;
}

double broken_set_difference(const std::vector<std::int64_t>& run,
                             const std::vector<std::int64_t>& reference) {
  std::vector<std::int64_t> differ;
  std::set_symmetric_difference(run.begin(), run.end(), reference.begin(), reference.end(),
                                std::back_inserter(differ));
  return static_cast<double>(differ.size()) /
         static_cast<double>(std::max<std::size_t>(reference.size(), 1));
}

ReferenceFacts reference_facts(const RunResult& reference) {
  return {first_break_lambda(reference), final_broken_set(reference), fault_angles(reference)};
}

void fill_from_run(StudyRow& row, const RunResult& run, const ReferenceFacts& reference) {
  row.breaks = std::count_if(run.events.begin(), run.events.end(),
                             [](const BreakEvent& e) { return e.mode != BreakMode::precut; });
  row.first_break_lambda = first_break_lambda(run);
  // A reference that first breaks at lambda = 0 (under gravity alone) has no relative
  // error to measure against: the column stays blank.
  if (row.first_break_lambda && reference.first_break && *reference.first_break != 0) {
    row.first_break_error = std::abs(*row.first_break_lambda - *reference.first_break) /
                            std::abs(*reference.first_break);
  }
  row.broken_set_difference = broken_set_difference(final_broken_set(run), reference.broken);
  row.wall_seconds = run.summary.wall_seconds;
  row.solves = run.summary.solves;
  row.faults = fault_angles(run);
  row.angle_differences = angle_differences(row.faults, reference.faults);
}

StudyResult run_study(const Scene& scene, const StudyOptions& options) {
  StudyResult study{scene.name, options.command_line, utc_timestamp(), {}};
  StopOnRequest control;
  const RunOptions run_options{options.command_line, options.run_progress, &control};
  // A run, or nothing when a stop was asked for during it (between its events, or inside
  // one of its solves).
  auto run_unless_stopped = [&](const Scene& variant) -> std::optional<RunResult> {
    try {
      RunResult run = run_scene(variant, run_options);
      if (run.summary.complete) return run;
    } catch (const StopWithinEvent&) {
    }
    return std::nullopt;
  };
  auto report = [&](const StudyRow& row) {
    study.rows.push_back(row);
    if (options.on_row) options.on_row(row);
  };

  // Every increment is checked before the reference runs, which may take long.
  for (const double increment : options.increments)
    check_step_count(scene.loading.total, increment, "--increments: the increment");
  if (options.reference_increment)
    check_step_count(scene.loading.total, *options.reference_increment, "the reference increment");

  // 1. The reference: event-driven, or fixed-step at a fine increment when asked.
  ReferenceFacts facts;
  {
    StudyRow row;
    row.reference = true;
    Scene variant;
    if (options.reference_increment) {
      row.method = "fixed";
      row.increment = *options.reference_increment;
      variant = run_variant(scene, SteppingMethod::fixed, *options.reference_increment,
                            scene.solver.method);
    } else {
      row.method = "event";
      variant = run_variant(scene, SteppingMethod::event, 0, scene.solver.method);
    }
    const std::optional<RunResult> reference = run_unless_stopped(variant);
    if (!reference) {
      study.stopped = true;
      return study;
    }
    check_result_finite(*reference);  // as `latfrac run` would before writing it
    facts = reference_facts(*reference);
    fill_from_run(row, *reference, facts);
    report(row);
  }

  // 2. The fixed-step runs with the scene's solver, then (if asked) with relaxation.
  std::vector<std::pair<std::string, EquilibriumMethod>> methods{{"fixed", scene.solver.method}};
  if (options.relaxation) methods.push_back({"fixed+relaxation", EquilibriumMethod::relaxation});
  for (const auto& [name, solver] : methods) {
    for (double increment : options.increments) {
      StudyRow row;
      row.method = name;
      row.increment = increment;
      try {
        const std::optional<RunResult> run =
            run_unless_stopped(run_variant(scene, SteppingMethod::fixed, increment, solver));
        if (!run) {
          study.stopped = true;
          return study;
        }
        check_result_finite(*run);  // a row of NaN would read as a result
        fill_from_run(row, *run, facts);
      } catch (const InputError& error) {
        row.status = RunStatus::not_available;
        row.note = error.what();
      } catch (const std::exception& error) {
        row.status = RunStatus::failed;
        row.note = error.what();
      }
      report(row);
    }
  }
  return study;
}

std::string progress_line(const StudyRow& row) {
  std::string line = method_label(row) + (row.reference ? " (reference)" : "") + ": ";
  if (row.status != RunStatus::ok) return line + to_string(row.status) + ": " + row.note;
  return line + std::to_string(row.breaks) + " breaks, " + significant(row.wall_seconds, 3) + " s";
}

}  // namespace latfrac
