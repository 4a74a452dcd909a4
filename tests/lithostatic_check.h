// Test helper: how far a gravity-loaded state is from the lithostatic stress of uniaxial
// strain, sigma_zz = -rho g depth and sigma_xx = nu / (1 - nu) sigma_zz.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "latfrac/mechanics/model.h"
#include "latfrac/mechanics/node_stress.h"
#include "latfrac/scene/scene.h"

namespace latfrac::testing {

// The depth of the discrete body's free surface: half a row pitch above the top row, since
// each node carries the weight of a row-pitch-thick slab.
inline double surface_height(const Lattice& lattice) {
  return lattice.extent.z() + lattice.row_pitch / 2;
}

struct LithostaticError {
  int checked = 0;      // nodes compared
  double zz = 0, xx = 0;  // the worst relative errors in sigma_zz and in sigma_xx / sigma_zz
};

// Compares the virial stress of the mid-body nodes: away from the top and base rows, and
// more than the body's height from the side faces, whose nodes have fewer bonds and shed
// weight into a boundary layer that decays over about the height (docs/model.md).
inline LithostaticError lithostatic_error(const Scene& scene, const Model& model,
                                          const Vector& displacement) {
  const Lattice& lattice = model.lattice;
  const std::vector<double> stress = node_stresses(model, displacement);
  const double surface = surface_height(lattice);
  const double rho_g = scene.material.density * scene.gravity->g;
  const double nu = scene.material.poisson;
  LithostaticError error;
  for (std::int64_t n = 0; n < lattice.node_count(); ++n) {
    const Vec3& p = lattice.positions[n];
    const bool mid_body =
        p.z() > 0.2 * lattice.extent.z() && p.z() < 0.8 * lattice.extent.z() &&
        std::abs(p.x() - lattice.extent.x() / 2) < 0.15 * lattice.extent.x() &&
        (lattice.dim == 2 || std::abs(p.y() - lattice.extent.y() / 2) < 0.15 * lattice.extent.y());
    if (!mid_body) continue;
    const double expected_zz = -rho_g * (surface - p.z());
    error.zz = std::max(error.zz, std::abs(stress[n * 6 + 2] / expected_zz - 1));
    error.xx =
        std::max(error.xx, std::abs(stress[n * 6 + 0] / (nu / (1 - nu) * stress[n * 6 + 2]) - 1));
    ++error.checked;
  }
  return error;
}

}  // namespace latfrac::testing
