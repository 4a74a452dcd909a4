// Fault reports as a readable table and as JSON.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>

#include "latfrac/analysis/fault_analysis.h"

namespace latfrac {

namespace {

std::string format(const char* pattern, auto... values) {
  char buffer[256];
  std::snprintf(buffer, sizeof buffer, pattern, values...);
  return buffer;
}

// Shortest round-trip form; JSON has no NaN or infinity, so those become null.
std::string json_number(double value) {
  if (!std::isfinite(value)) return "null";
  if (value == 0) value = 0;  // no "-0"
  char buffer[32];
  const auto written = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, written.ptr);
}

std::string dip_direction_text(int direction) {
  return direction > 0 ? "+x" : direction < 0 ? "-x" : "-";
}

std::string json_side(int direction) {
  if (direction == 0) return "null";
  std::string side = "\"";
  side += dip_direction_text(direction);
  side += '"';
  return side;
}

}  // namespace

double share_outside_graben(const FaultReport& report) {
  if (!report.graben) return 1;
  if (report.moved_bonds == 0) return 0;
  const Graben& graben = report.grabens[*report.graben];
  const std::int64_t inside =
      report.faults[graben.left_fault].bonds + report.faults[graben.right_fault].bonds;
  return static_cast<double>(report.moved_bonds - inside) / static_cast<double>(report.moved_bonds);
}

double graben_motion_share(const FaultReport& report) {
  if (!report.graben) return 0;
  const Graben& graben = report.grabens[*report.graben];
  return report.faults[graben.left_fault].motion_share +
         report.faults[graben.right_fault].motion_share;
}

namespace {

// "622.8 m", or "not measured" when a side of the graben has no surface node (NaN).
std::string subsidence_text(const Graben& graben) {
  if (!std::isfinite(graben.surface_subsidence)) return "not measured (no surface node on a side)";
  return format("%.5g m", graben.surface_subsidence);
}

// "2 (dips to +x, dip 60.3, alpha 29.7)": a fault by its table number.
std::string fault_text(const FaultReport& report, std::size_t f) {
  const Fault& fault = report.faults[f];
  return format("%zu (dips to %s, dip %.1f, alpha %.1f)", f + 1,
                dip_direction_text(fault.dip_direction).c_str(), fault.dip_deg, fault.alpha_deg);
}

// The graben's faults, the pre-cut fault and the wall faults, a line each.
std::string roles_text(const FaultReport& report) {
  std::string text = "\nThe faults that matter (roles: docs/fault-analysis.md)\n  graben: ";
  if (report.graben) {
    const Graben& graben = report.grabens[*report.graben];
    text += "faults " + fault_text(report, graben.left_fault) + " and " +
            fault_text(report, graben.right_fault) + "; subsidence " + subsidence_text(graben) +
            format(
                "; %.0f %% of the broken bonds outside these two, "
                "%.0f %% of the relative motion on them\n",
                100 * share_outside_graben(report), 100 * graben_motion_share(report));
  } else {
    text += "none\n";
  }
  text += "  pre-cut fault: ";
  if (report.precut_fault) {
    text += fault_text(report, *report.precut_fault);
    if (report.faults[*report.precut_fault].role == FaultRole::graben)
      text += ", also a graben fault";
    text += "\n";
  } else {
    text += report.precut_bonds == 0 ? "none (the run has no pre-cut)\n"
                                     : "none (no fault reaches the pre-cut)\n";
  }
  std::string walls;
  for (std::size_t f = 0; f < report.faults.size(); ++f)
    if (report.faults[f].role == FaultRole::wall)
      walls += (walls.empty() ? "" : ", ") + std::to_string(f + 1);
  return text + "  wall faults: " + (walls.empty() ? "none" : walls) + "\n";
}

// {"fault": 1, "side": "+x", "dip_deg": 60.3, "alpha_deg": 29.7 (no closing brace).
std::string json_fault_angles(const FaultReport& report, std::size_t f) {
  const Fault& fault = report.faults[f];
  return "{\"fault\": " + std::to_string(f) + ", \"side\": " + json_side(fault.dip_direction) +
         ", \"dip_deg\": " + json_number(fault.dip_deg) +
         ", \"alpha_deg\": " + json_number(fault.alpha_deg);
}

std::string json_roles(const FaultReport& report) {
  std::string json =
      ", \"precut_bonds\": " + std::to_string(report.precut_bonds) + ", \"graben\": ";
  if (report.graben) {
    const Graben& graben = report.grabens[*report.graben];
    json += "{\"index\": " + std::to_string(*report.graben) + ", \"faults\": [" +
            json_fault_angles(report, graben.left_fault) + "}, " +
            json_fault_angles(report, graben.right_fault) +
            "}], \"subsidence_m\": " + json_number(graben.surface_subsidence) +
            ", \"share_outside\": " + json_number(share_outside_graben(report)) +
            ", \"motion_share\": " + json_number(graben_motion_share(report)) + "}";
  } else {
    json += "null";
  }
  json += ", \"precut_fault\": ";
  if (report.precut_fault) {
    const Fault& fault = report.faults[*report.precut_fault];
    json += json_fault_angles(report, *report.precut_fault) + ", \"role\": \"" +
            to_string(fault.role) + "\", \"distance_m\": " + json_number(fault.precut_distance) +
            "}";
  } else {
    json += "null";
  }
  return json;
}

}  // namespace

std::string to_text(const FaultReport& report) {
  const bool three_d = report.dim == 3;
  std::string text = format("Faults at lambda = %g: %lld broken bonds (pre-cuts excluded); ",
                            report.lambda, static_cast<long long>(report.broken_bonds));
  if (report.min_offset > 0) {
    text += format("%lld of them moved by %g m or more, analysed; ",
                   static_cast<long long>(report.moved_bonds), report.min_offset);
  }
  text += format("clusters: %zu, grabens: %zu\n", report.faults.size(), report.grabens.size());
  if (report.faults.empty()) return text;

  text +=
      "dip: from horizontal; alpha = 90 - dip: to the vertical (sigma1); "
      "dips to: the side the fault descends towards\n"
      "opening, slip, dip-slip: the mean offset across its bonds, m (dip-slip > 0: normal "
      "sense); motion: its share of the relative motion across the bonds analysed\n";
  text +=
      format("%4s %6s %8s %8s %6s %6s %6s %7s %11s %9s %11s", "#", "role", "bonds", "tensile",
             "shear", "dip", "alpha", "dips to", three_d ? "area m^2" : "length m", "rms m", "x m");
  if (three_d) text += format(" %11s", "y m");
  text += format(" %11s %9s %9s %9s %7s\n", "z m", "opening", "slip", "dip-slip", "motion");
  for (std::size_t f = 0; f < report.faults.size(); ++f) {
    const Fault& fault = report.faults[f];
    text += format("%4zu %6s %8lld %8.2f %6.2f %6.1f %6.1f %7s %11.4g %9.3g %11.5g", f + 1,
                   to_string(fault.role), static_cast<long long>(fault.bonds), fault.tensile_share,
                   fault.shear_share, fault.dip_deg, fault.alpha_deg,
                   dip_direction_text(fault.dip_direction).c_str(), fault.extent, fault.fit_rms,
                   fault.centroid[0]);
    if (three_d) text += format(" %11.5g", fault.centroid[1]);
    text += format(" %11.5g %9.3g %9.3g", fault.centroid[2], fault.opening, fault.slip);
    // No dip-slip on a vertical or horizontal fault (NaN): "-", as its side is.
    text += std::isfinite(fault.dip_slip) ? format(" %9.3g", fault.dip_slip) : format(" %9s", "-");
    text += format(" %6.0f%%", 100 * fault.motion_share);
    if (fault.diffuse)
      text += format("  diffuse (variance ratio %.2f, rms %.3g m, fill share %.2f): not a fault",
                     fault.variance_ratio, fault.fit_rms, fault.fill_share);
    text += "\n";
  }
  if (report.grabens.empty()) return text + roles_text(report);

  text += "\nGrabens (subsidence: surface outside minus between the faults; positive: down)\n";
  text += format("%6s %6s %13s %13s %13s %15s\n", "left", "right", "left x m", "right x m",
                 "apex depth m", "subsidence m");
  for (const Graben& graben : report.grabens) {
    text += format(
        "%6zu %6zu %13.5g %13.5g %13.5g %15s\n", graben.left_fault + 1, graben.right_fault + 1,
        graben.left_surface_x, graben.right_surface_x, graben.apex_depth,
        std::isfinite(graben.surface_subsidence) ? format("%.5g", graben.surface_subsidence).c_str()
                                                 : "-");
  }
  return text + roles_text(report);
}

std::string to_json(const FaultReport& report) {
  std::string json =
      "{\"dim\": " + std::to_string(report.dim) + ", \"lambda\": " + json_number(report.lambda) +
      ", \"broken_bonds\": " + std::to_string(report.broken_bonds) +
      ", \"min_offset_m\": " + json_number(report.min_offset) +
      ", \"moved_bonds\": " + std::to_string(report.moved_bonds) +
      ", \"relative_motion_m\": " + json_number(report.relative_motion) + ", \"faults\": [";
  for (std::size_t f = 0; f < report.faults.size(); ++f) {
    const Fault& fault = report.faults[f];
    if (f > 0) json += ", ";
    json += "{\"bonds\": " + std::to_string(fault.bonds) +
            ", \"tensile_share\": " + json_number(fault.tensile_share) +
            ", \"shear_share\": " + json_number(fault.shear_share) + ", \"centroid\": [" +
            json_number(fault.centroid[0]) + ", " + json_number(fault.centroid[1]) + ", " +
            json_number(fault.centroid[2]) + "], \"normal\": [" + json_number(fault.normal[0]) +
            ", " + json_number(fault.normal[1]) + ", " + json_number(fault.normal[2]) +
            "], \"dip_deg\": " + json_number(fault.dip_deg) +
            ", \"alpha_deg\": " + json_number(fault.alpha_deg) +
            ", \"dip_direction\": " + std::to_string(fault.dip_direction) +
            ", \"extent\": " + json_number(fault.extent) +
            ", \"fit_rms\": " + json_number(fault.fit_rms) +
            ", \"variance_ratio\": " + json_number(fault.variance_ratio) +
            ", \"fill_share\": " + json_number(fault.fill_share) +
            ", \"diffuse\": " + (fault.diffuse ? "true" : "false") +
            ", \"wall_share\": " + json_number(fault.wall_share) +
            ", \"precut_distance\": " + json_number(fault.precut_distance) +
            ", \"opening_m\": " + json_number(fault.opening) +
            ", \"slip_m\": " + json_number(fault.slip) +
            ", \"dip_slip_m\": " + json_number(fault.dip_slip) +
            ", \"motion_share\": " + json_number(fault.motion_share) + ", \"role\": \"" +
            to_string(fault.role) + "\"}";
  }
  json += "], \"grabens\": [";
  for (std::size_t g = 0; g < report.grabens.size(); ++g) {
    const Graben& graben = report.grabens[g];
    if (g > 0) json += ", ";
    json += "{\"left_fault\": " + std::to_string(graben.left_fault) +
            ", \"right_fault\": " + std::to_string(graben.right_fault) +
            ", \"left_surface_x\": " + json_number(graben.left_surface_x) +
            ", \"right_surface_x\": " + json_number(graben.right_surface_x) +
            ", \"apex_depth\": " + json_number(graben.apex_depth) +
            ", \"surface_subsidence\": " + json_number(graben.surface_subsidence) + "}";
  }
  json += ']';
  json += json_roles(report);
  json += '}';
  return json;
}

}  // namespace latfrac
