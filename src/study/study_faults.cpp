// The study's fault angles: the graben's and the pre-cut fault's, against the reference's.
#include <algorithm>
#include <cmath>

#include "latfrac/analysis/fault_analysis.h"
#include "latfrac/study/study.h"
#include "study_format.h"

namespace latfrac {

namespace {

TrackedFault tracked(const Fault& fault) {
  return {fault.alpha_deg, fault.dip_direction, fault.normal};
}

std::optional<double> difference(const std::optional<TrackedFault>& run,
                                 const std::optional<TrackedFault>& reference) {
  if (!run || !reference) return std::nullopt;
  return angle_between(*run, *reference);
}

// Whether the run has every fault the reference has, each within kAngleMatchDeg of it.
bool angles_match(const StudyRow& row, const FaultAngles& reference) {
  const std::pair<const std::optional<TrackedFault>*, const std::optional<double>*> pairs[] = {
      {&reference.graben_left, &row.angle_differences.graben_left},
      {&reference.graben_right, &row.angle_differences.graben_right},
      {&reference.precut, &row.angle_differences.precut}};
  return std::all_of(std::begin(pairs), std::end(pairs), [](const auto& pair) {
    return !*pair.first || (*pair.second && **pair.second <= kAngleMatchDeg);
  });
}

// "graben alpha 29.7 and 30 deg; pre-cut fault alpha 30 deg, towards -x"
std::string angles_text(const FaultAngles& faults) {
  std::string text;
  if (faults.graben_left && faults.graben_right)
    text = "graben alpha " + significant(faults.graben_left->alpha_deg, 3) + " and " +
           significant(faults.graben_right->alpha_deg, 3) + " deg";
  if (faults.precut) {
    if (!text.empty()) text += "; ";
    text += "pre-cut fault alpha " + significant(faults.precut->alpha_deg, 3) + " deg";
    if (faults.precut->side != 0) text += ", towards " + side_text(faults.precut->side);
  }
  return text;
}

}  // namespace

FaultAngles fault_angles(const RunResult& run) {
  FaultAngles angles;
  if (run.snapshots.empty()) return angles;
  const FaultReport report = analyze_faults(run, run.snapshots.size() - 1);
  if (report.graben) {
    const Graben& graben = report.grabens[*report.graben];
    angles.graben_left = tracked(report.faults[graben.left_fault]);
    angles.graben_right = tracked(report.faults[graben.right_fault]);
  }
  if (report.precut_fault) angles.precut = tracked(report.faults[*report.precut_fault]);
  return angles;
}

double angle_between(const TrackedFault& a, const TrackedFault& b) {
  double cosine = 0;
  for (int k = 0; k < 3; ++k) cosine += a.normal[k] * b.normal[k];
  return std::acos(std::min(1.0, std::abs(cosine))) * 180.0 / M_PI;
}

AngleDifferences angle_differences(const FaultAngles& run, const FaultAngles& reference) {
  return {difference(run.graben_left, reference.graben_left),
          difference(run.graben_right, reference.graben_right),
          difference(run.precut, reference.precut)};
}

std::string angle_interpretation(const StudyResult& study) {
  const StudyRow* reference = reference_row(study);
  if (!reference || reference->status != RunStatus::ok) return "";
  const FaultAngles& faults = reference->faults;
  if (!faults.graben_left && !faults.precut)
    return "Fault angles: the reference has no graben and no pre-cut fault; there is no angle "
           "to compare.";
  const StudyRow* chosen = nullptr;
  for (const StudyRow& row : study.rows) {
    if (row.reference || row.status != RunStatus::ok || !row.increment) continue;
    if (!angles_match(row, faults)) continue;
    if (!chosen || *row.increment > *chosen->increment ||
        (*row.increment == *chosen->increment && row.wall_seconds < chosen->wall_seconds))
      chosen = &row;
  }
  const std::string within =
      significant(kAngleMatchDeg, 3) + " deg of the reference's (" + angles_text(faults) + ")";
  if (!chosen) return "Fault angles: no increment has every fault angle within " + within + ".";
  return "Fault angles: the largest increment with every fault angle within " + within + " is " +
         method_label(*chosen) + " (" + angles_text(chosen->faults) + ").";
}

}  // namespace latfrac
