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

#include "latfrac/criteria/criterion.h"
#include "latfrac/fracture/fracture_run.h"
#include "latfrac/fracture/initial_supports.h"
#include "latfrac/scene/model_builder.h"
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

// The direction of largest spread of at least two points (unit, either sign).
inline Eigen::Vector2d principal_axis(const std::vector<Eigen::Vector2d>& points) {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (const auto& p : points) scatter += (p - mean) * (p - mean).transpose();
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(scatter).eigenvectors().col(1);
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
  Eigen::Vector2d along = principal_axis(points);
  if (along.y() < 0) along = -along;                     // pointing up
  crack.degrees = std::atan2(-along.x(), along.y()) * 180 / std::numbers::pi;
  return crack;
}

// A rotated load: the same plate with every face node moved as the uniaxial strain
// lambda (m (x) m) would move it, m at `load_degrees` from x in the x-z plane, and a
// slit through the middle perpendicular to m, `notch_length` long. An isotropic body
// cracks on from both ends of the slit, perpendicular to the load; a lattice with
// directions of its own can turn the crack towards them. Returns the crack's direction
// (the broken bonds' principal axis) from the slit's, in degrees, in (-90, 90].
inline CrackDirection rotated_load_crack(LatticeKind kind, double load_degrees,
                                         std::uint64_t seed) {
  Scene scene = notched_plate(kind, 0.0, seed);
  scene.precuts.clear();
  const double angle = load_degrees * std::numbers::pi / 180;
  const Vec3 load(std::cos(angle), 0, std::sin(angle)), along(-std::sin(angle), 0, std::cos(angle));
  const Vec3 centre(plate_size / 2 + 0.25, 0, plate_size / 2 + 0.25);
  const Vec3 from = centre - notch_length / 2 * along, to = centre + notch_length / 2 * along;
  scene.precuts.push_back({{from.x(), 0, from.z()}, {to.x(), 0, to.z()}, {}, {}, {}});
  const std::shared_ptr<const FailureCriterion> criterion =
      make_criterion(*scene.strength, scene.lattice.dim);
  Model model = build_model(scene, criterion.get());
  const Lattice& lattice = model.lattice;
  std::array<FaceCondition, face_count> faces;
  faces.fill(FaceCondition::fixed);
  DofMap dofs = build_dof_map(lattice, faces);
  const Vec3 middle = lattice.extent / 2;
  for (std::int64_t n = 0; n < lattice.node_count(); ++n) {
    const Vec3 rate = load * load.dot(lattice.positions[n] - middle);  // per unit lambda
    if (dofs.free_index[2 * n] < 0) dofs.prescribed_rate[2 * n] = rate.x();
    if (dofs.free_index[2 * n + 1] < 0) dofs.prescribed_rate[2 * n + 1] = rate.z();
  }
  ModelEditor(model).set_dofs(dofs);
  RunResult result;
  record_lattice(model, result);
  result.fragments = prepare_supports(model, "rotated load");
  EquilibriumSolver solver(model, scene.solver);
  ProgressLine progress(false);
  FractureRun fracture(model, criterion, scene.strength->bond_stress,
                       {scene.loading.total, scene.stepping, {}}, scene.solver, solver, progress,
                       result);
  fracture.run();

  std::vector<Eigen::Vector2d> points;
  for (const BreakEvent& event : result.events) {
    if (event.mode == BreakMode::precut) continue;
    const Bond& bond = lattice.bonds[event.bond];
    const Vec3 mid = 0.5 * (lattice.positions[bond.i] + lattice.positions[bond.j]);
    points.emplace_back(mid.x(), mid.z());
  }
  CrackDirection crack;
  crack.bonds = static_cast<int>(points.size());
  if (points.size() < 2) return crack;
  const Eigen::Vector2d axis = principal_axis(points);
  // The signed angle from the slit's direction to the axis, folded into (-90, 90].
  double degrees = (std::atan2(axis.y(), axis.x()) - std::atan2(along.z(), along.x())) * 180 /
                   std::numbers::pi;
  while (degrees > 90) degrees -= 180;
  while (degrees <= -90) degrees += 180;
  crack.degrees = degrees;
  return crack;
}

}  // namespace latfrac::testing
