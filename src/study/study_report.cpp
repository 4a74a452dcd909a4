// The study's files: the reading of its rows, study.csv, study.md, and writing all three.
#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "latfrac/base/atomic_write.h"
#include "latfrac/base/error.h"
#include "latfrac/study/study.h"
#include "study_format.h"

namespace latfrac {

std::vector<std::string> study_interpretation(const StudyResult& study) {
  const StudyRow* reference = reference_row(study);
  std::vector<const StudyRow*> runs;
  for (const StudyRow& row : study.rows)
    if (!row.reference && row.status == RunStatus::ok && row.increment && row.broken_set_difference)
      runs.push_back(&row);
  if (!reference || runs.empty())
    return {"No fixed-step run finished: there is nothing to compare with the reference.", "", ""};

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
  return {first, second, angle_interpretation(study)};
}

namespace {

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

// A fault's alpha with the side it descends to, "29.7 (+x)"; "n/a" when there is none.
std::string fault_cell(const std::optional<TrackedFault>& fault) {
  if (!fault) return "n/a";
  const std::string side = side_text(fault->side);
  return significant(fault->alpha_deg, 3) + (side.empty() ? "" : " (" + side + ")");
}

std::string difference_cell(const std::optional<double>& difference) {
  return difference ? significant(*difference, 2) : "n/a";
}

std::optional<double> alpha(const std::optional<TrackedFault>& fault) {
  if (!fault) return std::nullopt;
  return fault->alpha_deg;
}

}  // namespace

std::string study_csv(const StudyResult& study) {
  std::ostringstream csv;
  csv << "role,method,increment,status,breaks,first_break_lambda,first_break_error,"
         "broken_set_difference,graben_left_alpha,graben_right_alpha,precut_alpha,precut_side,"
         "graben_left_difference,graben_right_difference,precut_difference,wall_seconds,solves,"
         "note\n";
  for (const StudyRow& row : study.rows) {
    const bool ok = row.status == RunStatus::ok;
    const AngleDifferences& differences = row.angle_differences;
    csv << (row.reference ? "reference" : "run") << ',' << row.method << ','
        << optional_text(row.increment, 0) << ',' << to_string(row.status) << ','
        << (ok ? std::to_string(row.breaks) : "") << ',' << optional_text(row.first_break_lambda, 0)
        << ',' << optional_text(row.first_break_error, 0) << ','
        << optional_text(row.broken_set_difference, 0) << ','
        << optional_text(alpha(row.faults.graben_left), 0) << ','
        << optional_text(alpha(row.faults.graben_right), 0) << ','
        << optional_text(alpha(row.faults.precut), 0) << ','
        << (row.faults.precut ? side_text(row.faults.precut->side) : "") << ','
        << optional_text(differences.graben_left, 0) << ','
        << optional_text(differences.graben_right, 0) << ',' << optional_text(differences.precut, 0)
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
        "difference (%) | graben alpha left / right | vs reference (deg) | pre-cut fault alpha "
        "| vs reference (deg) | wall s | solves |\n"
     << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  std::vector<std::string> notes;
  for (const StudyRow& row : study.rows) {
    md << "| " << row.method << (row.reference ? " (reference)" : "") << " | "
       << (row.increment ? increment_text(*row.increment) : "") << " | ";
    if (row.status != RunStatus::ok) {
      md << to_string(row.status) << " (see below) | | | | | | | | | |\n";
      notes.push_back(method_label(row) + ": " + to_string(row.status) + ": " + row.note);
      continue;
    }
    const std::string percent =
        row.broken_set_difference ? significant(100 * *row.broken_set_difference, 3) : "";
    const FaultAngles& faults = row.faults;
    const AngleDifferences& differences = row.angle_differences;
    const std::string graben = faults.graben_left && faults.graben_right
                                   ? significant(faults.graben_left->alpha_deg, 3) + " / " +
                                         significant(faults.graben_right->alpha_deg, 3)
                                   : "n/a";
    md << row.breaks << " | " << optional_text(row.first_break_lambda, 6) << " | "
       << optional_text(row.first_break_error, 3) << " | " << percent << " | " << graben << " | "
       << difference_cell(differences.graben_left) << " / "
       << difference_cell(differences.graben_right) << " | " << fault_cell(faults.precut) << " | "
       << difference_cell(differences.precut) << " | " << significant(row.wall_seconds, 3) << " | "
       << row.solves << " |\n";
  }
  md << "\n";
  for (const std::string& note : notes) md << "- " << note << "\n";
  if (!notes.empty()) md << "\n";
  md << "## Reading\n\n";
  for (const std::string& line : study_interpretation(study))
    if (!line.empty()) md << line << "\n";
  md << "\nGraben alpha: the angle to the vertical of the graben's left fault (descending "
        "towards +x) and right fault (towards -x); pre-cut fault alpha: that of the fault "
        "through or from the tip of the pre-cut, with the side it descends to "
        "(docs/fault-analysis.md, \"Roles\"); n/a when the run has none. vs reference: the "
        "angle between the run's fault and the reference's. First-break error: blank when the "
        "reference first breaks at lambda = 0. Plot: study.png (error against wall time, "
        "log-log).\n";
  return md.str();
}

void write_study(const StudyResult& study, const std::string& out_dir) {
  make_directory(out_dir);
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
