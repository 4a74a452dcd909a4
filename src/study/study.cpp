// The convergence study: the runs, their comparison with the reference, study.csv and study.md.
#include "latfrac/study/study.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "latfrac/base/atomic_write.h"
#include "latfrac/base/error.h"
#include "latfrac/analysis/fault_analysis.h"
#include "latfrac/scene/run.h"

namespace latfrac {
namespace {

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

// The shortest decimal that reads back as the same double.
std::string full_precision(double value) {
  char text[32];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, value);
    if (std::strtod(text, nullptr) == value) break;
  }
  return text;
}

std::string significant(double value, int digits) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  return text;
}

// What every run is compared with.
struct ReferenceFacts {
  std::optional<double> first_break;
  std::vector<std::int64_t> broken;
};

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

// alpha (degrees to the vertical) of the largest fault that is a fault, not a shattered
// cloud (docs/fault-analysis.md); empty when the run has none.
std::optional<double> main_fault_angle(const RunResult& run) {
  if (run.snapshots.empty()) return std::nullopt;
  const FaultReport report = analyze_faults(run, run.snapshots.size() - 1);
  for (const Fault& fault : report.faults) {
    if (!fault.diffuse) return fault.alpha_deg;
  }
  return std::nullopt;
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
  row.fault_angle = main_fault_angle(run);
}

std::string method_label(const StudyRow& row) {
  std::string label = row.method;
  if (row.increment) label += " ds=" + increment_text(*row.increment);
  return label;
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string optional_text(const std::optional<double>& value, int digits) {
  if (!value) return "";
  return digits > 0 ? significant(*value, digits) : full_precision(*value);
}

const StudyRow* reference_row(const StudyResult& study) {
  for (const StudyRow& row : study.rows)
    if (row.reference) return &row;
  return nullptr;
}

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

StudyResult run_study(const Scene& scene, const StudyOptions& options) {
  StudyResult study{scene.name, options.command_line, utc_timestamp(), {}};
  RunOptions run_options{options.command_line, options.run_progress};
  auto report = [&](const StudyRow& row) {
    study.rows.push_back(row);
    if (options.on_row) options.on_row(row);
  };

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
    const RunResult reference = run_scene(variant, run_options);
    facts = {first_break_lambda(reference), final_broken_set(reference)};
    fill_from_run(row, reference, facts);
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
        fill_from_run(
            row,
            run_scene(run_variant(scene, SteppingMethod::fixed, increment, solver), run_options),
            facts);
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

std::vector<std::string> study_interpretation(const StudyResult& study) {
  const StudyRow* reference = reference_row(study);
  std::vector<const StudyRow*> runs;
  for (const StudyRow& row : study.rows)
    if (!row.reference && row.status == RunStatus::ok && row.increment && row.broken_set_difference)
      runs.push_back(&row);
  if (!reference || runs.empty())
    return {"No fixed-step run finished: there is nothing to compare with the reference.", ""};

  // The largest increment among those within the threshold (the cheaper one on a tie).
  auto largest_within = [&](double threshold) -> const StudyRow* {
    const StudyRow* best = nullptr;
    for (const StudyRow* row : runs) {
      if (*row->broken_set_difference > threshold) continue;
      if (!best || *row->increment > *best->increment ||
          (*row->increment == *best->increment && row->wall_seconds < best->wall_seconds))
        best = row;
    }
    return best;
  };
  std::string first;
  const StudyRow* chosen = largest_within(0);
  if (chosen) {
    first = "The largest increment that reproduces the reference's broken set exactly is " +
            method_label(*chosen) + " (" + std::to_string(chosen->breaks) + " breaks).";
  } else if ((chosen = largest_within(0.01))) {
    first =
        "No increment reproduces the reference's broken set exactly; the largest within 1 % is " +
        method_label(*chosen) + " (difference " +
        significant(100 * *chosen->broken_set_difference, 3) + " %).";
  } else {
    chosen = *std::min_element(runs.begin(), runs.end(), [](const StudyRow* a, const StudyRow* b) {
      return *a->broken_set_difference < *b->broken_set_difference;
    });
    first = "No increment comes within 1 % of the reference's broken set; the closest is " +
            method_label(*chosen) + " (difference " +
            significant(100 * *chosen->broken_set_difference, 3) + " %): try smaller increments.";
  }
  std::string second = "It took " + significant(chosen->wall_seconds, 3) + " s and " +
                       std::to_string(chosen->solves) + " solves";
  if (reference->wall_seconds > 0 && reference->solves > 0) {
    second += ": " + significant(chosen->wall_seconds / reference->wall_seconds, 3) +
              " times the reference's wall time (" + significant(reference->wall_seconds, 3) +
              " s) and " + significant(double(chosen->solves) / reference->solves, 3) +
              " times its solves (" + std::to_string(reference->solves) + ")";
  }
  second += ".";
  return {first, second};
}

std::string study_csv(const StudyResult& study) {
  std::ostringstream csv;
  csv << "role,method,increment,status,breaks,first_break_lambda,first_break_error,broken_set_"
         "difference,"
         "fault_angle,wall_seconds,solves,note\n";
  for (const StudyRow& row : study.rows) {
    const bool ok = row.status == RunStatus::ok;
    csv << (row.reference ? "reference" : "run") << ',' << row.method << ','
        << optional_text(row.increment, 0) << ',' << to_string(row.status) << ','
        << (ok ? std::to_string(row.breaks) : "") << ',' << optional_text(row.first_break_lambda, 0)
        << ',' << optional_text(row.first_break_error, 0) << ','
        << optional_text(row.broken_set_difference, 0) << ',' << optional_text(row.fault_angle, 0)
        << ',' << (ok ? full_precision(row.wall_seconds) : "") << ','
        << (ok ? std::to_string(row.solves) : "") << ',' << csv_field(row.note) << '\n';
  }
  return csv.str();
}

std::string study_markdown(const StudyResult& study) {
  std::ostringstream md;
  md << "# Convergence study: " << study.scene_name << "\n\n"
     << "- command: `" << study.command_line << "`\n"
     << "- date: " << study.date << "\n"
     << "- errors are against the reference (first row); columns: docs/convergence-study.md\n\n"
     << "| method | increment | breaks | first-break lambda | first-break error | broken-set "
        "difference (%) "
        "| fault angle | wall s | solves |\n"
     << "|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  std::vector<std::string> notes;
  for (const StudyRow& row : study.rows) {
    md << "| " << row.method << (row.reference ? " (reference)" : "") << " | "
       << (row.increment ? increment_text(*row.increment) : "") << " | ";
    if (row.status != RunStatus::ok) {
      md << to_string(row.status) << " (see below) | | | | | | |\n";
      notes.push_back(method_label(row) + ": " + to_string(row.status) + ": " + row.note);
      continue;
    }
    const std::string percent =
        row.broken_set_difference ? significant(100 * *row.broken_set_difference, 3) : "";
    md << row.breaks << " | " << optional_text(row.first_break_lambda, 6) << " | "
       << optional_text(row.first_break_error, 3) << " | " << percent << " | "
       << (row.fault_angle ? significant(*row.fault_angle, 3) : "n/a") << " | "
       << significant(row.wall_seconds, 3) << " | " << row.solves << " |\n";
  }
  md << "\n";
  for (const std::string& note : notes) md << "- " << note << "\n";
  if (!notes.empty()) md << "\n";
  md << "## Reading\n\n";
  for (const std::string& line : study_interpretation(study))
    if (!line.empty()) md << line << "\n";
  md << "\nFault angle: alpha (to the vertical) of the largest fault that fault analysis does not "
        "flag as diffuse (docs/fault-analysis.md); n/a when there is none. First-break error: "
        "blank "
        "when the reference first breaks at lambda = 0. Plot: study.png (error against wall time, "
        "log-log).\n";
  return md.str();
}

void write_study(const StudyResult& study, const std::string& out_dir) {
  std::error_code error;
  std::filesystem::create_directories(out_dir, error);
  if (error) throw Error("cannot create output directory '" + out_dir + "': " + error.message());
  const std::filesystem::path dir(out_dir);
  auto write_text = [](const std::string& path, const std::string& text) {
    write_atomically(path, [&](const std::string& partial) {
      std::ofstream file(partial, std::ios::binary);
      file << text;
      file.close();
      if (!file) throw Error("cannot write '" + partial + "': " + std::strerror(errno));
    });
  };
  write_text((dir / "study.csv").string(), study_csv(study));
  write_text((dir / "study.md").string(), study_markdown(study));
  write_study_plot(study, (dir / "study.png").string());
}

}  // namespace latfrac
