// Number and label formats shared by the study's tables, progress lines and readings.
#pragma once

#include <optional>
#include <string>

#include "latfrac/base/number_text.h"
#include "latfrac/study/study.h"

namespace latfrac {

// Empty for no value; `digits` significant digits, or (0) every digit needed.
inline std::string optional_text(const std::optional<double>& value, int digits) {
  if (!value) return "";
  return digits > 0 ? significant(*value, digits) : full_precision(*value);
}

// "fixed ds=1e-3", or "event".
inline std::string method_label(const StudyRow& row) {
  std::string label = row.method;
  if (row.increment) label += " ds=" + increment_text(*row.increment);
  return label;
}

// The side a fault descends to, "+x" or "-x"; "" for neither.
inline std::string side_text(int side) { return side > 0 ? "+x" : side < 0 ? "-x" : ""; }

inline const StudyRow* reference_row(const StudyResult& study) {
  for (const StudyRow& row : study.rows)
    if (row.reference) return &row;
  return nullptr;
}

}  // namespace latfrac
