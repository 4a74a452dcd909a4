// The scene: everything a problem file says, resolved and validated, in SI units.
//
// A scene names its effects: an absent optional section means the effect is off
// (no [gravity], no gravity; no [strength], purely elastic; no [contact], no contact
// springs). The problem-file reader (problem_file.h) is the only producer of a Scene;
// docs/problem-files.md documents every key, its unit, default and allowed range.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace latfrac {

enum class Face { x_min, x_max, y_min, y_max, z_min, z_max };
inline constexpr int face_count = 6;

// What a face of the box imposes on the nodes that belong to it.
//   free:      nothing
//   roller:    the displacement normal to the face is zero
//   fixed:     the whole displacement is zero
//   extension: the displacement along the face's axis is lambda * (X - centre), i.e.
//              -lambda L/2 and +lambda L/2 on the x walls; tangential components free
enum class FaceCondition { free, roller, fixed, extension };

enum class Criterion { tensile, tensile_or_shear, elliptic, drucker_prager };
// Where a bond's normal and shear stresses come from (docs/criteria.md):
//   strain: sigma_n = E eps_n, tau = G gamma, from the bond's own strains (model.md section 2)
//   tensor: the bond's stress tensor (the mean of its nodes' virial stresses) resolved on
//           the bond direction, sigma_n = n.S.n, tau = |S n - sigma_n n|; this carries the
//           lithostatic confinement that bond strains miss
//   critical_plane: the same tensor on the plane where the criterion is largest (the
//           material point's criterion: Rankine for tensile); the bond direction plays no
//           part, so crack paths do not follow the lattice's rows
enum class BondStress { strain, tensor, critical_plane };
enum class SteppingMethod { event, fixed };
enum class EquilibriumMethod { newton, relaxation };
enum class Ordering { metis, nesdis, amd };

struct LatticeSpec {
  int dim = 2;                          // 2 (plane-strain x-z section) or 3
  double spacing = 0;                   // a, m
  std::array<double, 3> size{0, 0, 0};  // box extent along x, y, z in m (y unused in 2-D)
  bool next_nearest = true;             // 3-D only: next-nearest bonds at sqrt(2) a
};

struct Material {
  double density = 0;  // kg/m^3
  double young = 0;    // Pa
  double poisson = 0;  // dimensionless, -1 < nu <= 1/4
};

struct Strength {
  Criterion criterion = Criterion::elliptic;
  double sigma0 = 0;                     // tensile strength, Pa
  std::optional<double> tau0;            // shear cohesion, Pa, when given directly
  std::optional<double> friction_angle;  // psi, degrees
  double tau0_factor = 1;                // m in tau0 = m sigma0 (1 + sin psi) / (2 cos psi)
  BondStress bond_stress = BondStress::strain;  // not used by drucker_prager (always the tensor)
};

struct Gravity {
  double g = 9.81;  // m/s^2
};

struct Loading {
  double total = 0;  // final extension strain lambda (negative: compression)
};

struct Stepping {
  SteppingMethod method = SteppingMethod::event;
  double increment = 0;  // strain increment ds for the fixed-step method
};

// A pre-cut fault: bonds whose segment crosses it start broken.
// 2-D: the segment from -> to in the x-z plane (y components are 0).
// 3-D: the rectangle corner + s edge1 + t edge2, s, t in [0, 1].
struct Precut {
  std::array<double, 3> from{0, 0, 0}, to{0, 0, 0};                       // 2-D, m
  std::array<double, 3> corner{0, 0, 0}, edge1{0, 0, 0}, edge2{0, 0, 0};  // 3-D, m
};

struct Contact {
  bool enabled = true;
};

// A horizontal layer z_min <= z < z_max with its own material and strength; a bond
// belongs to the layer that holds its midpoint. Unset values inherit the scene's.
struct Layer {
  double z_min = 0, z_max = 0;  // m
  Material material;
  std::optional<double> sigma0, tau0;  // Pa
};

// Random bond strength: sigma0 and tau0 of each bond are multiplied by a factor drawn
// uniformly from [1 - spread, 1 + spread] by a generator seeded with `seed`.
struct Heterogeneity {
  double spread = 0;
  std::uint64_t seed = 0;
};

struct Output {
  std::vector<double> snapshots;  // lambda values at which to store a snapshot
  double exaggeration = 1;        // displacement magnification in pictures
  bool picture = true;            // write a PNG of the final state
};

struct SolverOptions {
  EquilibriumMethod method = EquilibriumMethod::newton;
  double tolerance = 1e-10;  // residual, relative to the load
  int max_iterations = 50;   // Newton iterations
  Ordering ordering = Ordering::metis;
  int refactor_every = 200;  // factor updates before a fresh factorization
  double relaxation_omega = 1.8;
  double relaxation_tolerance = 1e-8;
  long relaxation_max_sweeps = 100000;
};

struct Scene {
  std::string name;
  std::string description;
  LatticeSpec lattice;
  Material material;
  std::array<FaceCondition, face_count> faces{
      FaceCondition::extension, FaceCondition::extension,  // x_min, x_max
      FaceCondition::roller,    FaceCondition::roller,     // y_min, y_max
      FaceCondition::roller,    FaceCondition::free};      // z_min, z_max
  std::optional<Strength> strength;
  std::optional<Gravity> gravity;
  Loading loading;
  Stepping stepping;
  std::vector<Precut> precuts;
  std::optional<Contact> contact;
  std::vector<Layer> layers;
  std::optional<Heterogeneity> heterogeneity;
  bool large_kinematics = false;
  Output output;
  SolverOptions solver;

  std::string source_path;  // the problem file, for messages and provenance
  std::string source_text;  // its full text
};

const char* to_string(Criterion criterion);
const char* to_string(BondStress source);
const char* to_string(FaceCondition condition);
const char* to_string(Face face);

}  // namespace latfrac
