// Fault traces and graben triangles on sections and maps, fault planes in the oblique view.
#include "fault_overlay.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <optional>

#include "colour_map.h"

namespace latfrac {
namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();
constexpr Colour graben_colour{235, 165, 20};
constexpr Colour plane_colour{235, 120, 20};

Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

Vec3 plus(const Vec3& a, const Vec3& b, double scale = 1) {
  return {a[0] + scale * b[0], a[1] + scale * b[1], a[2] + scale * b[2]};
}

// The exaggerated mean displacement of the nodes within two spacings of the fault's centroid
// (reference): a fault that opened lies between blocks that moved apart, and the mean keeps
// its line between them. The nearest node's when none is that close.
Vec3 fault_shift(const SceneView& view, const RunResult& result, const Snapshot& snapshot,
                 const Fault& fault) {
  Vec3 sum{0, 0, 0};
  std::size_t count = 0, nearest = 0;
  double best = infinity;
  for (std::size_t node = 0; node < result.node_count(); ++node) {
    const double* p = &result.positions[3 * node];
    const double d = std::hypot(p[0] - fault.centroid[0], p[1] - fault.centroid[1],
                                p[2] - fault.centroid[2]);
    if (d < best) best = d, nearest = node;
    if (d > 2 * view.spacing) continue;
    sum = plus(sum, {snapshot.displacement[3 * node], snapshot.displacement[3 * node + 1],
                     snapshot.displacement[3 * node + 2]});
    ++count;
  }
  const double* u = &snapshot.displacement[3 * nearest];
  const Vec3 mean = count > 0 ? Vec3{sum[0] / count, sum[1] / count, sum[2] / count}
                              : Vec3{u[0], u[1], u[2]};
  return {view.exaggeration * mean[0], view.exaggeration * mean[1], view.exaggeration * mean[2]};
}

// The bounding box of the reference positions, m.
std::pair<Vec3, Vec3> reference_box(const RunResult& result) {
  Vec3 low{infinity, infinity, infinity}, high{-infinity, -infinity, -infinity};
  for (std::size_t node = 0; node < result.node_count(); ++node)
    for (int axis = 0; axis < 3; ++axis) {
      low[axis] = std::min(low[axis], result.positions[3 * node + axis]);
      high[axis] = std::max(high[axis], result.positions[3 * node + axis]);
    }
  return {low, high};
}

// The length of the block along a fault's strike (horizontal, in its plane), m: a 3-D
// fault's area over this is its length down the dip.
double strike_length(const RunResult& result, const Fault& fault) {
  const auto [low, high] = reference_box(result);
  const Vec3 strike = cross(fault.normal, {0, 0, 1});
  const double norm = std::hypot(strike[0], strike[1]);
  if (norm < 1e-9) return std::max(high[0] - low[0], high[1] - low[1]);
  double length = infinity;
  for (int axis = 0; axis < 2; ++axis)
    if (std::abs(strike[axis]) > 1e-9 * norm)
      length = std::min(length, (high[axis] - low[axis]) * norm / std::abs(strike[axis]));
  return length;
}

// A fault's trace in the view plane, a h + b v = c, with the segment drawn of it.
struct Trace {
  double a = 0, b = 0, c = 0;
  ViewPoint from, to;  // `to` is the upper end
};

std::optional<Trace> trace_of(const SceneView& view, const RunResult& result, const Fault& fault,
                              const Vec3& shift) {
  Trace trace;
  const Vec3& n = fault.normal;
  trace.a = dot(n, view.right), trace.b = dot(n, view.up);
  const double norm = std::hypot(trace.a, trace.b);
  if (norm < 1e-6) return std::nullopt;  // the fault lies in the view plane
  const Vec3 centre = plus(Vec3{fault.centroid[0], fault.centroid[1], fault.centroid[2]}, shift);
  trace.c = dot(n, centre) - view.plane * dot(n, view.away);
  // From the point nearest the centroid, along the trace, within the fault's length and
  // the window.
  const ViewPoint c = view.project(centre);
  const double off = (trace.a * c.h + trace.b * c.v - trace.c) / (norm * norm);
  const ViewPoint middle{c.h - off * trace.a, c.v - off * trace.b};
  const double dh = -trace.b / norm, dv = trace.a / norm;
  double half = result.scene.dim == 2 ? fault.extent / 2 : infinity;
  if (result.scene.dim == 3 && view.kind == PictureView::section)
    half = 0.5 * fault.extent / strike_length(result, fault);
  double t0 = -half, t1 = half;
  auto clip = [&](double p, double d, double low, double high) {
    if (std::abs(d) < 1e-12) {
      if (p < low || p > high) t0 = infinity;
      return;
    }
    const double a = (low - p) / d, b = (high - p) / d;
    t0 = std::max(t0, std::min(a, b)), t1 = std::min(t1, std::max(a, b));
  };
  clip(middle.h, dh, view.h_min, view.h_max);
  clip(middle.v, dv, view.v_min, view.v_max);
  if (!(t0 < t1)) return std::nullopt;
  trace.from = {middle.h + t0 * dh, middle.v + t0 * dv};
  trace.to = {middle.h + t1 * dh, middle.v + t1 * dv};
  if (trace.to.v < trace.from.v) std::swap(trace.from, trace.to);
  return trace;
}

std::string angles_text(const Fault& fault) {
  char text[64];
  std::snprintf(text, sizeof text, "α %.1f°, dip %.1f°", fault.alpha_deg, fault.dip_deg);
  return text;
}

// Text on a white, slightly see-through box, starting at (x, y), moved left if need be to
// end inside the frame.
void boxed_text(Canvas& canvas, const PictureLayout& layout, double x, double y,
                const std::string& text) {
  const double font = layout.font, width = canvas.text_width(text);
  const double left = std::max(layout.frame.left, std::min(x, layout.frame.right - width - 0.3 * font));
  canvas.colour(paper_colour, 0.8);
  canvas.rectangle(left - 0.2 * font, y - 0.6 * font, width + 0.4 * font, 1.2 * font);
  canvas.fill();
  canvas.colour(ink_colour);
  canvas.text(left, y, text, Align::start, Align::centre);
}

// The graben between two traces: from where each meets the surface down to where they meet.
void draw_graben(Canvas& canvas, const PictureLayout& layout, const Trace& left,
                 const Trace& right, double surface, const Graben& graben, FaultLayer layer) {
  const double det = left.a * right.b - left.b * right.a;
  if (std::abs(left.a) < 1e-9 || std::abs(right.a) < 1e-9 || std::abs(det) < 1e-12) return;
  const ViewPoint apex{(left.c * right.b - left.b * right.c) / det,
                       (left.a * right.c - left.c * right.a) / det};
  const ViewPoint l{(left.c - left.b * surface) / left.a, surface};
  const ViewPoint r{(right.c - right.b * surface) / right.a, surface};
  if (layer == FaultLayer::lines) return;
  if (layer == FaultLayer::areas) {
    canvas.colour(graben_colour, 0.3);
    canvas.move_to(layout.x(l), layout.y(l));
    canvas.line_to(layout.x(r), layout.y(r));
    canvas.line_to(layout.x(apex), layout.y(apex));
    canvas.close_path();
    canvas.fill();
    return;
  }
  char text[96];
  if (std::isfinite(graben.surface_subsidence))
    std::snprintf(text, sizeof text, "graben, subsided %.3g m", graben.surface_subsidence);
  else
    std::snprintf(text, sizeof text, "graben");
  const ViewPoint label{0.5 * (l.h + r.h), surface - 0.3 * (surface - apex.v)};
  boxed_text(canvas, layout, layout.x(label) - 0.5 * canvas.text_width(text), layout.y(label), text);
}

// The fault plane cut by the reference block (shifted), limited to its depth range.
std::vector<Vec3> plane_polygon(const RunResult& result, const Fault& fault, const Vec3& shift) {
  auto [low, high] = reference_box(result);
  low = plus(low, shift), high = plus(high, shift);
  const Vec3& n = fault.normal;
  const Vec3 centre = plus(Vec3{fault.centroid[0], fault.centroid[1], fault.centroid[2]}, shift);
  const double half_depth =
      0.5 * fault.extent / strike_length(result, fault) * std::sin(fault.dip_deg * std::numbers::pi / 180);
  low[2] = std::max(low[2], centre[2] - half_depth);
  high[2] = std::min(high[2], centre[2] + half_depth);
  std::vector<Vec3> points;
  for (int axis = 0; axis < 3; ++axis)  // the 12 edges: along `axis`, at each corner of the others
    for (int corner = 0; corner < 4; ++corner) {
      Vec3 a = low;
      const int first = (axis + 1) % 3, second = (axis + 2) % 3;
      a[first] = corner & 1 ? high[first] : low[first];
      a[second] = corner & 2 ? high[second] : low[second];
      Vec3 b = a;
      b[axis] = high[axis];
      const double da = dot(n, plus(a, centre, -1)), db = dot(n, plus(b, centre, -1));
      if ((da < 0) == (db < 0) || da == db) continue;
      points.push_back(plus(a, plus(b, a, -1), da / (da - db)));
    }
  if (points.size() < 3) return {};
  // In order round the plane.
  Vec3 mid{};
  for (const Vec3& p : points) mid = plus(mid, p, 1.0 / points.size());
  const Vec3 e1 = cross(n, std::abs(n[2]) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0});
  const Vec3 e2 = cross(n, e1);
  std::sort(points.begin(), points.end(), [&](const Vec3& p, const Vec3& q) {
    return std::atan2(dot(plus(p, mid, -1), e2), dot(plus(p, mid, -1), e1)) <
           std::atan2(dot(plus(q, mid, -1), e2), dot(plus(q, mid, -1), e1));
  });
  return points;
}

}  // namespace

std::vector<LegendEntry> draw_faults(Canvas& canvas, const SceneView& view,
                                     const PictureLayout& layout, const RunResult& result,
                                     const Snapshot& snapshot, const FaultReport& report,
                                     FaultLayer layer) {
  const bool labels = layer == FaultLayer::labels;
  std::vector<std::optional<Trace>> traces(report.faults.size());
  std::size_t drawn = 0;
  for (std::size_t i = 0; i < report.faults.size(); ++i) {
    const Fault& fault = report.faults[i];
    if (fault.diffuse) continue;
    const Vec3 shift = fault_shift(view, result, snapshot, fault);
    if (view.kind == PictureView::oblique) {
      const std::vector<Vec3> polygon = plane_polygon(result, fault, shift);
      if (polygon.empty()) continue;
      ++drawn;
      const Vec3* top = &polygon.front();
      for (const Vec3& p : polygon) {
        const ViewPoint at = view.project(p);
        if (layer == FaultLayer::areas)
          &p == &polygon.front() ? canvas.move_to(layout.x(at), layout.y(at))
                                 : canvas.line_to(layout.x(at), layout.y(at));
        if (p[2] > (*top)[2]) top = &p;
      }
      if (labels) {
        const ViewPoint at = view.project(*top);
        boxed_text(canvas, layout, layout.x(at), layout.y(at) - layout.font, angles_text(fault));
        continue;
      }
      if (layer != FaultLayer::areas) continue;
      canvas.close_path();
      canvas.colour(plane_colour, 0.25);
      canvas.fill_preserve();
      canvas.colour(plane_colour);
      canvas.line_width(std::max(1.0, layout.font / 8));
      canvas.stroke();
      continue;
    }
    traces[i] = trace_of(view, result, fault, shift);
    if (!traces[i]) continue;
    ++drawn;
    if (labels) {
      boxed_text(canvas, layout, layout.x(traces[i]->to) + 0.4 * layout.font,
                 layout.y(traces[i]->to) + 0.2 * layout.font, angles_text(fault));
      continue;
    }
    if (layer != FaultLayer::lines) continue;
    canvas.colour(ink_colour);
    canvas.line_width(std::max(1.5, layout.font / 6));
    canvas.dash(0.8 * layout.font, 0.4 * layout.font);
    canvas.segment(layout.x(traces[i]->from), layout.y(traces[i]->from), layout.x(traces[i]->to),
                   layout.y(traces[i]->to));
    canvas.stroke();
    canvas.dash(0, 0);
  }

  std::vector<LegendEntry> entries;
  const bool along_x = view.kind == PictureView::section && view.right[0] == 1;
  std::size_t grabens = 0;
  if (along_x) {
    double surface = -infinity;
    for (std::size_t node = 0; node < result.node_count(); ++node)
      surface = std::max(surface, result.positions[3 * node + 2]);
    for (const Graben& graben : report.grabens)
      if (traces[graben.left_fault] && traces[graben.right_fault]) {
        draw_graben(canvas, layout, *traces[graben.left_fault], *traces[graben.right_fault],
                    surface, graben, layer);
        ++grabens;
      }
  }
  if (view.kind == PictureView::oblique)
    entries.push_back({LegendEntry::Symbol::swatch, mix(plane_colour, paper_colour, 0.6),
                       drawn > 0 ? "fitted fault plane" : "no fault fitted"});
  else
    entries.push_back({LegendEntry::Symbol::dashed_line, ink_colour,
                       drawn > 0 ? "fitted fault" : "no fault fitted"});
  if (grabens > 0)
    entries.push_back({LegendEntry::Symbol::swatch, mix(graben_colour, paper_colour, 0.7), "graben"});
  return entries;
}

}  // namespace latfrac
