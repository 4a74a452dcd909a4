// What a problem file's [strength] section asks for: the criterion, its strengths, and
// where a bond's stresses come from (docs/criteria.md).
#pragma once

#include <optional>

namespace latfrac {

enum class Criterion { tensile, tensile_or_shear, elliptic, drucker_prager };
const char* to_string(Criterion criterion);

// Where a bond's normal and shear stresses come from (docs/criteria.md):
//   strain: sigma_n = E eps_n, tau = G gamma, from the bond's own strains (model.md section 2)
//   tensor: the bond's stress tensor (the mean of its nodes' virial stresses) resolved on
//           the bond direction, sigma_n = n.S.n, tau = |S n - sigma_n n|; this carries the
//           lithostatic confinement that bond strains miss
//   critical_plane: the same tensor on the plane where the criterion is largest (the
//           material point's criterion: Rankine for tensile); the bond direction plays no
//           part, so crack paths do not follow the lattice's rows
enum class BondStress { strain, tensor, critical_plane };
const char* to_string(BondStress source);

struct Strength {
  Criterion criterion = Criterion::elliptic;
  double sigma0 = 0;                     // tensile strength, Pa
  std::optional<double> tau0;            // shear cohesion, Pa, when given directly
  std::optional<double> friction_angle;  // psi, degrees
  double tau0_factor = 1;                // m in tau0 = m sigma0 (1 + sin psi) / (2 cos psi)
  BondStress bond_stress = BondStress::strain;  // not used by drucker_prager (always the tensor)
  // mu_i: the shear strength grows with compression, tau0 + mu_i <-sigma_n>+ (0: it does
  // not; docs/criteria.md). Not used by tensile (no tau0) or drucker_prager (which has its
  // own pressure term).
  double internal_friction = 0;
};

}  // namespace latfrac
