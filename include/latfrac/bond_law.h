// The bond law: a bond's tension vector and tangent stiffness from its nodes' displacements.
//
// Small kinematics (the default) measures the relative displacement du = u_j - u_i
// against the reference direction n0:
//   dn = n0 . du (tension positive),  ds = du - dn n0,
//   t  = kn dn n0 + ks ds   (the force on node i; node j feels -t)
// which is linear in du, so the tangent is kn n0 n0' + ks (I - n0 n0').
// Every residual and every stiffness matrix in latfrac comes from one BondLaw object, so
// the large-kinematics law (current direction n) replaces it without touching assembly.
#pragma once

#include <Eigen/Core>
#include <memory>

namespace latfrac {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

// Normal and shear displacement of a bond, m.
struct BondDeformation {
  double normal = 0;     // dn, tension positive
  Vec3 shear = Vec3::Zero();  // ds
};

// A bond's reference geometry: unit vector n0 from node i to node j, and length L0 (m).
struct BondReference {
  const Vec3& direction;
  double length;
};

class BondLaw {
 public:
  virtual ~BondLaw() = default;
  // relative_displacement = u_j - u_i.
  virtual BondDeformation deformation(const BondReference& reference,
                                      const Vec3& relative_displacement) const = 0;
  virtual Vec3 tension(const BondReference& reference, const Vec3& relative_displacement, double kn,
                       double ks) const = 0;
  // d tension / d relative_displacement.
  virtual Mat3 tangent(const BondReference& reference, const Vec3& relative_displacement, double kn,
                       double ks) const = 0;
  // True when tension is linear in the displacement (equilibrium paths are affine).
  virtual bool is_linear() const = 0;
};

class SmallKinematics final : public BondLaw {
 public:
  BondDeformation deformation(const BondReference& reference,
                              const Vec3& relative_displacement) const override;
  Vec3 tension(const BondReference& reference, const Vec3& relative_displacement, double kn,
               double ks) const override;
  Mat3 tangent(const BondReference& reference, const Vec3& relative_displacement, double kn,
               double ks) const override;
  bool is_linear() const override { return true; }
};

}  // namespace latfrac
