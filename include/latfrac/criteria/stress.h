// Stress at a point: Voigt tensors, their invariants, resolution on a plane, failure indices.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>

namespace latfrac {

// How a bond broke: the larger part of its failure index, or a pre-cut.
enum class BreakMode : std::int8_t { tensile = 0, shear = 1, precut = 2 };

// A failure index f (the bond fails when f >= 1) and the mode it would break in.
struct FailureIndex {
  double value = 0;
  BreakMode mode = BreakMode::tensile;
};

// Voigt order xx, yy, zz, yz, xz, xy (Pa, tension positive).
using VoigtStress = std::array<double, 6>;

// A stress tensor resolved on the unit direction n: the normal stress n.S.n and the shear
// traction vector S n - (n.S.n) n (Pa, tension positive). Linear in S.
struct ResolvedStress {
  double normal = 0;
  Eigen::Vector3d shear = Eigen::Vector3d::Zero();
};
ResolvedStress resolve_on(const VoigtStress& stress, const Eigen::Vector3d& n);
// The symmetric 3 x 3 matrix of a Voigt stress.
Eigen::Matrix3d stress_matrix(const VoigtStress& stress);

// I1 = trace.
double first_invariant(const VoigtStress& stress);
// The symmetric bilinear form whose diagonal is J2: (s_a : s_b) / 2 with s the deviators,
// Voigt shear components counted twice. Written with differences of normal components so
// that a large mean stress does not cancel against the deviator.
double j2_product(const VoigtStress& a, const VoigtStress& b);
inline double second_deviatoric_invariant(const VoigtStress& s) { return j2_product(s, s); }

}  // namespace latfrac
