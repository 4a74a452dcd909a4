// Virial node stresses: the branch form on regular lattices, the facet-centroid form on
// random ones.
#include "latfrac/mechanics/node_stress.h"

namespace latfrac {
namespace {

// Per node, the sum over its intact bonds of arm (x) force. In 2-D only the x-z block is
// summed: the y row and column stay zero, and the sweep runs after every event.
std::vector<Mat3> bond_dyads(const Model& model, const Vector& displacement) {
  const Lattice& lattice = model.lattice;
  std::vector<Mat3> sum(lattice.node_count(), Mat3::Zero());
  const bool plane = lattice.dim == 2;
  auto add = [plane](Mat3& to, const Vec3& arm, const Vec3& t) {
    if (!plane) {
      to.noalias() += arm * t.transpose();
      return;
    }
    to(0, 0) += arm.x() * t.x();
    to(0, 2) += arm.x() * t.z();
    to(2, 0) += arm.z() * t.x();
    to(2, 2) += arm.z() * t.z();
  };
  for (std::int64_t b = 0; b < lattice.bond_count(); ++b) {
    if (!model.intact(b)) continue;
    const Bond& bond = lattice.bonds[b];
    const Vec3 t = model.bond_law().tension(model.springs(b), PairState::intact,
                                            model.bond_displacement(displacement, b));
    if (lattice.is_random()) {
      // t acts on i, -t on j; each node's arm reaches to the facet's centroid.
      const Vec3& centroid = lattice.bond_facet_centroid[b];
      add(sum[bond.i], centroid - lattice.positions[bond.i], t);
      add(sum[bond.j], lattice.positions[bond.j] - centroid, t);
      continue;
    }
    const Vec3 d0 = lattice.bond_direction[b] * lattice.bond_length[b];
    add(sum[bond.i], d0, t);
    add(sum[bond.j], d0, t);
  }
  return sum;
}

}  // namespace

std::vector<double> node_stresses(const Model& model, const Vector& displacement) {
  const Lattice& lattice = model.lattice;
  const std::vector<Mat3> sum = bond_dyads(model, displacement);
  std::vector<double> voigt(lattice.node_count() * 6);
  const double scale = 1.0 / (2 * lattice.node_volume);
  for (std::int64_t n = 0; n < lattice.node_count(); ++n) {
    const double weight = lattice.is_random() ? 1.0 / lattice.node_volumes[n] : scale;
    const Mat3 s = 0.5 * weight * (sum[n] + sum[n].transpose());
    double* v = &voigt[n * 6];
    v[0] = s(0, 0);
    v[2] = s(2, 2);
    v[1] = lattice.dim == 2 ? model.node_poisson[n] * (s(0, 0) + s(2, 2)) : s(1, 1);
    v[3] = s(1, 2);
    v[4] = s(0, 2);
    v[5] = s(0, 1);
  }
  return voigt;
}

}  // namespace latfrac
