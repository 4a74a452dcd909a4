// Test and benchmark helper: a notched plate pulled apart, and the direction of its crack.
//
// The load is along x (the x walls move apart; the base is a roller, the top free, no
// gravity), so a tensile crack should run perpendicular to it: vertical. The notch, a
// pre-cut 8 spacings long from the top at the plate's middle, leans `notch_degrees` from
// the vertical. A lattice with no direction of its own lets the crack turn from the
// notch's tip to the vertical, whatever the lean; the triangular lattice offers rows at 30
// degrees from the vertical (and horizontal ones), and its crack can follow them instead.
// Rotating the load would need walls that are not axis-aligned; leaning the notch asks
// the same question (does the crack follow the load, or a direction the geometry
// suggests?) with the walls as they are.
#pragma once

#include <Eigen/Eigenvalues>
#include <cmath>
#include <numbers>

#include "latfrac/scene/run.h"
#include "scenes.h"

namespace latfrac::testing {

inline constexpr double notch_length = 8;  // spacings
inline constexpr double plate_size = 40;   // spacings, both sides

// Bond strains with the tensile criterion: the reading in which docs/validation.md found
// the triangular lattice's cracks following its rows.
inline Scene notched_plate(LatticeKind kind, double notch_degrees, std::uint64_t seed) {
  Scene scene = box_scene(2, 1.0, {plate_size, 0, plate_size}, false);
  scene.lattice.kind = kind;
  scene.lattice.seed = seed;
  scene.strength = strength_of(Criterion::tensile, 10e6);  // sigma0 / E = 1e-4
  scene.strength->bond_stress = BondStress::strain;
  scene.loading.total = 0.8e-4;  // below the far field's own strength
  scene.stepping = {SteppingMethod::event, 0};
  scene.output.picture = false;
  // The tip at the middle, a quarter spacing off the triangular lattice's node columns.
  const double lean = notch_degrees * std::numbers::pi / 180;
  const double tip_x = plate_size / 2 + 0.25, tip_z = plate_size - notch_length;
  const double reach = notch_length + 1;  // from the tip up beyond the top
  scene.precuts.push_back({{tip_x - reach * std::sin(lean), 0, tip_z + reach * std::cos(lean)},
                           {tip_x, 0, tip_z},
                           {},
                           {},
                           {}});
  return scene;
}

struct CrackDirection {
  int bonds = 0;       // broken bonds below the notch's tip
  double degrees = 0;  // from the vertical, positive leaning like the notch (towards -x up)
};

// The line fitted (principal axis) through the midpoints of the bonds broken below the
// notch's tip.
inline CrackDirection crack_direction(const RunResult& result) {
  const double tip_z = plate_size - notch_length;
  std::vector<Eigen::Vector2d> points;
  for (const BreakEvent& event : result.events) {
    if (event.mode == BreakMode::precut) continue;
    const std::int64_t i = result.bonds[2 * event.bond], j = result.bonds[2 * event.bond + 1];
    const Eigen::Vector2d mid(0.5 * (result.positions[3 * i] + result.positions[3 * j]),
                              0.5 * (result.positions[3 * i + 2] + result.positions[3 * j + 2]));
    if (mid.y() < tip_z) points.push_back(mid);
  }
  CrackDirection crack;
  crack.bonds = static_cast<int>(points.size());
  if (points.size() < 2) return crack;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (const auto& p : points) scatter += (p - mean) * (p - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(scatter);
  Eigen::Vector2d along = eigen.eigenvectors().col(1);  // the largest spread
  if (along.y() < 0) along = -along;                     // pointing up
  crack.degrees = std::atan2(-along.x(), along.y()) * 180 / std::numbers::pi;
  return crack;
}

}  // namespace latfrac::testing
