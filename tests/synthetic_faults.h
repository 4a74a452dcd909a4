// Synthetic runs for the fault-analysis tests: small lattices whose bonds are broken by hand.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

#include "latfrac/fracture/run_result.h"

namespace latfrac::testing {

constexpr double kDegree = M_PI / 180.0;
using Xyz = std::array<double, 3>;

// A result with the given nodes, bonds between every pair at a distance in `lengths` (within
// 1e-9), and one snapshot with every bond intact and nothing displaced.
inline RunResult lattice_result(int dim, const std::vector<Xyz>& nodes,
                                const std::vector<double>& lengths) {
  RunResult result;
  result.scene.dim = dim;
  result.scene.spacing = 1.0;
  for (const Xyz& p : nodes) result.positions.insert(result.positions.end(), p.begin(), p.end());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    for (std::size_t j = i + 1; j < nodes.size(); ++j) {
      const double distance = std::hypot(nodes[j][0] - nodes[i][0], nodes[j][1] - nodes[i][1],
                                         nodes[j][2] - nodes[i][2]);
      for (std::size_t kind = 0; kind < lengths.size(); ++kind) {
        if (std::abs(distance - lengths[kind]) > 1e-9) continue;
        result.bonds.push_back(static_cast<std::int64_t>(i));
        result.bonds.push_back(static_cast<std::int64_t>(j));
        result.bond_kind.push_back(static_cast<std::int8_t>(kind));
      }
    }
  }
  Snapshot snapshot;
  snapshot.lambda = 0.04;
  snapshot.displacement.assign(result.positions.size(), 0.0);
  snapshot.bond_intact.assign(result.bond_count(), 1);
  result.snapshots.push_back(snapshot);
  return result;
}

// The 2-D triangular lattice at spacing 1: rows along x, odd rows shifted by half a spacing.
// `symmetric`: odd rows one node shorter, so that x -> columns - 1 - x maps the lattice onto
// itself.
inline RunResult triangular(int columns = 60, int rows = 40, bool symmetric = false) {
  std::vector<Xyz> nodes;
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < columns - (symmetric && j % 2 ? 1 : 0); ++i) {
      nodes.push_back({i + (j % 2 ? 0.5 : 0.0), 0.0, j * std::sqrt(3.0) / 2});
    }
  }
  return lattice_result(2, nodes, {1.0});
}

// A simple cubic box of nx x ny x nz nodes at spacing 1, with edge and face-diagonal bonds.
inline RunResult cubic_box(int nx, int ny, int nz) {
  std::vector<Xyz> nodes;
  for (int k = 0; k < nz; ++k) {
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) nodes.push_back({double(i), double(j), double(k)});
    }
  }
  return lattice_result(3, nodes, {1.0, std::sqrt(2.0)});
}

inline RunResult cubic(int size = 16) { return cubic_box(size, size, size); }

inline double top_z(const RunResult& result) {
  double top = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < result.node_count(); ++i)
    top = std::max(top, result.positions[3 * i + 2]);
  return top;
}

inline Xyz midpoint(const RunResult& result, std::size_t bond) {
  Xyz m;
  for (int c = 0; c < 3; ++c) {
    m[c] = 0.5 * (result.positions[3 * result.bonds[2 * bond] + c] +
                  result.positions[3 * result.bonds[2 * bond + 1] + c]);
  }
  return m;
}

// Breaks (in the last snapshot) every intact bond whose midpoint passes `select`; returns them.
inline std::vector<std::int64_t> break_where(RunResult& result,
                                             const std::function<bool(const Xyz&)>& select) {
  std::vector<std::int64_t> broken;
  auto& intact = result.snapshots.back().bond_intact;
  for (std::size_t b = 0; b < result.bond_count(); ++b) {
    if (intact[b] && select(midpoint(result, b))) {
      intact[b] = 0;
      broken.push_back(static_cast<std::int64_t>(b));
    }
  }
  return broken;
}

// Distance in the x-z plane from p to the line through (x0, z0) rising at `angle_deg` towards +x.
inline double distance_to_line(const Xyz& p, double x0, double z0, double angle_deg) {
  const double c = std::cos(angle_deg * kDegree), s = std::sin(angle_deg * kDegree);
  return std::abs((p[0] - x0) * s - (p[2] - z0) * c);
}

// Distance in the x-z plane from p to the segment from a to b (each given as x, z).
inline double distance_to_segment(const Xyz& p, std::array<double, 2> a, std::array<double, 2> b) {
  const double dx = b[0] - a[0], dz = b[1] - a[1];
  const double along =
      std::clamp(((p[0] - a[0]) * dx + (p[2] - a[1]) * dz) / (dx * dx + dz * dz), 0.0, 1.0);
  return std::hypot(p[0] - a[0] - along * dx, p[2] - a[1] - along * dz);
}

// Breaks the bonds within half a spacing of the polyline through `corners` (x, z), so the
// midpoints scatter like a lattice crack's, about 0.3 spacings (rms) about each segment.
inline std::vector<std::int64_t> break_along(RunResult& result,
                                             const std::vector<std::array<double, 2>>& corners) {
  return break_where(result, [&](const Xyz& m) {
    for (std::size_t c = 0; c + 1 < corners.size(); ++c) {
      if (distance_to_segment(m, corners[c], corners[c + 1]) < 0.5) return true;
    }
    return false;
  });
}

inline void add_events(RunResult& result, const std::vector<std::int64_t>& bonds,
                       std::int8_t mode) {
  for (const std::int64_t b : bonds)
    result.events.push_back({0.01, b, 1.0, static_cast<BreakMode>(mode), 0});
}

// The fitted dip of a band of bonds within half a spacing of a line: its midpoints scatter
// about sigma = 0.3 spacings across the line, systematically (the lattice's staircase), over a
// length L of 20 to 35 spacings with n = 2 L points. Were the scatter random, the direction's
// standard error sigma sqrt(12) / (L sqrt(n)) would be 0.5 deg for L = 20 and 0.2 deg for
// L = 35. The tests allow 1 deg, twice the larger, as the analysis's other tests do
// (docs/fault-analysis.md, "Limitations").
constexpr double kDipToleranceDeg = 1.0;

// The layout of graben_with_precut: a symmetric lattice 80 m wide (x = 0 .. 80) and 34.6 m
// high (41 rows).
constexpr int kGrabenColumns = 81, kGrabenRows = 41;
constexpr double kGrabenWidth = kGrabenColumns - 1;
constexpr double kCutX = 50.25, kCutDepth = 6;  // the pre-cut, m

struct Layout {
  RunResult result;
  std::size_t wall = 0, graben = 0, precut = 0, other = 0;  // bonds broken for each
};

// A wall fault along the left wall (the bonds within 1.4 m of it, the whole height), a
// vertical pre-cut 6 m deep at x = 50.25 (break events of mode 2), a V graben whose left arm
// leaves the surface at x = 20 dipping left_dip towards +x and whose right arm leaves the
// pre-cut's tip dipping right_dip towards -x, the block between them lowered by 10 m, and a
// short vertical fault at x = 68. `mirrored`: the same reflected about x = 40 (the lattice is
// symmetric about it).
inline Layout graben_with_precut(double left_dip, double right_dip, bool mirrored) {
  Layout layout{triangular(kGrabenColumns, kGrabenRows, true)};
  RunResult& result = layout.result;
  const double top = top_z(result), tip_z = top - kCutDepth;
  const double left_cot = 1 / std::tan(left_dip * kDegree);
  const double right_cot = 1 / std::tan(right_dip * kDegree);
  // The arms meet at depth d below the surface: 20 + d cot(left) = 50.25 - (d - 6) cot(right).
  const double apex_depth = (kCutX - 20 + kCutDepth * right_cot) / (left_cot + right_cot);
  const double apex_x = 20 + apex_depth * left_cot, apex_z = top - apex_depth;
  auto mirror = [&](double x) { return mirrored ? kGrabenWidth - x : x; };
  auto in_layout = [&](auto select) {
    return [=](Xyz m) {
      m[0] = mirror(m[0]);
      return select(m);
    };
  };
  const auto precut = break_where(result, in_layout([&](const Xyz& m) {
                                    return std::abs(m[0] - kCutX) < 0.3 && m[2] > tip_z;
                                  }));
  add_events(result, precut, 2);
  layout.precut = precut.size();
  layout.wall = break_where(result, in_layout([](const Xyz& m) { return m[0] < 1.4; })).size();
  layout.graben =
      break_where(result, in_layout([&](const Xyz& m) {
                    return distance_to_segment(m, {20, top}, {apex_x, apex_z}) < 0.5 ||
                           distance_to_segment(m, {kCutX, tip_z}, {apex_x, apex_z}) < 0.5;
                  }))
          .size();
  layout.other = break_where(result, in_layout([](const Xyz& m) {
                               return std::abs(m[0] - 68.2) < 0.5 && m[2] > 5 && m[2] < 20;
                             }))
                     .size();
  auto& displacement = result.snapshots.back().displacement;
  for (std::size_t i = 0; i < result.node_count(); ++i) {
    const double x = mirror(result.positions[3 * i]), z = result.positions[3 * i + 2];
    const bool block =
        z > apex_z && x > 20 + (top - z) * left_cot && x < kCutX + (z - tip_z) * right_cot;
    if (block) displacement[3 * i + 2] = -10.0;
  }
  return layout;
}

}  // namespace latfrac::testing
