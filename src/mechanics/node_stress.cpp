// Virial node stresses: the branch form on regular lattices, the facet-centroid form on
// random ones.
#include "latfrac/mechanics/node_stress.h"

#include <initializer_list>

#include "latfrac/base/threads.h"

namespace latfrac {
namespace {

void add_dyad(bool plane, Mat3& to, const Vec3& arm, const Vec3& t) {
  if (!plane) {
    to.noalias() += arm * t.transpose();
    return;
  }
  to(0, 0) += arm.x() * t.x();
  to(0, 2) += arm.x() * t.z();
  to(2, 0) += arm.z() * t.x();
  to(2, 2) += arm.z() * t.z();
}

// The supports' forces on a random lattice's face nodes, each at its face piece: a held
// component's force is what balances the node's intact bonds (`bond_force`, their force
// on the node) and, with the loads, its weight. It goes to the piece whose normal is that
// axis, or else (a base held along x under a basal discontinuity) to the node's first.
void add_support_dyads(const Model& model, const std::vector<Vec3>& bond_force, bool with_loads,
                       std::vector<Mat3>& sum) {
  const Lattice& lattice = model.lattice;
  const int dim = lattice.dim;
  const std::vector<int> axes = lattice.axes();
  const auto& pieces = lattice.face_pieces;
  for (std::size_t first = 0; first < pieces.size();) {
    const std::int64_t node = pieces[first].node;
    std::size_t last = first;
    while (last < pieces.size() && pieces[last].node == node) ++last;
    for (int c = 0; c < dim; ++c) {
      const std::int64_t dof = node * dim + c;
      if (model.dofs().free_index[dof] >= 0) continue;
      const int axis = axes[c];
      double support = -bond_force[node][axis];
      if (with_loads) support -= model.external_force[dof];
      const FacePiece* piece = &pieces[first];
      for (std::size_t k = first; k < last; ++k)
        if (pieces[k].axis == axis) piece = &pieces[k];
      add_dyad(dim == 2, sum[node], piece->arm, support * Vec3::Unit(axis));
    }
    first = last;
  }
  // The overburden's pressure on the top face pieces, at their centroids (a held z is a
  // support's, counted above).
  if (!with_loads || model.top_pressure == 0) return;
  for (const FacePiece& piece : pieces) {
    if (!lattice.on_top(piece)) continue;
    if (model.dofs().free_index[piece.node * dim + (dim - 1)] < 0) continue;
    add_dyad(dim == 2, sum[piece.node], piece.arm,
             -model.top_pressure * piece.area * Vec3::UnitZ());
  }
}

// What a sweep over the bonds sums for one displacement field: per node, the sum over
// its intact bonds of arm (x) force, and on a random lattice with face pieces each node's
// force from its intact bonds (for the supports). A rate (`state` false) reads u_j - u_i
// alone: the bonds' prestretch is part of the state.
struct DyadSums {
  DyadSums(const Model& model, const Vector& u, bool state_field, bool with_force)
      : displacement(u),
        state(state_field),
        sum(model.lattice.node_count(), Mat3::Zero()),
        bond_force(with_force ? model.lattice.node_count() : 0, Vec3::Zero()) {}
  const Vector& displacement;
  bool state;
  std::vector<Mat3> sum;
  std::vector<Vec3> bond_force;
};

// Bond b's arm at its end n: on a random lattice from the node to the facet's centroid
// (t acts on i, -t on j), on a regular one the branch d0 for both ends.
Vec3 arm_at(const Lattice& lattice, std::int64_t b, std::int64_t n, bool end_j) {
  if (!lattice.is_random()) return lattice.bond_direction[b] * lattice.bond_length[b];
  const Vec3& centroid = lattice.bond_facet_centroid[b];
  return end_j ? Vec3(lattice.positions[n] - centroid) : Vec3(centroid - lattice.positions[n]);
}

// Adds a bond's tension t at its end n to a field's sums.
void add_at_end(bool plane, DyadSums& field, std::int64_t n, const Vec3& arm, const Vec3& t,
                bool end_j) {
  add_dyad(plane, field.sum[n], arm, t);
  if (field.bond_force.empty()) return;
  if (end_j) {
    field.bond_force[n] -= t;
  } else {
    field.bond_force[n] += t;
  }
}

Vec3 tension_of(const Model& model, std::int64_t b, const DyadSums& field) {
  const Vec3 du = field.state ? model.bond_displacement(field.displacement, b)
                              : model.relative_motion(field.displacement, b);
  return model.bond_law().tension(model.springs(b), PairState::intact, du);
}

// Sums the dyads of every intact bond into each field. In 2-D only the x-z block is
// summed: the y row and column stay zero. On one thread: one loop over the bonds, each
// added to its two ends. On more: the bonds' tensions (each bond on its own), then each
// node's sum over its bonds in bond order (Model::node_bonds), which adds the same terms
// in the same order: the same numbers on any number of threads.
void sum_dyads(const Model& model, std::initializer_list<DyadSums*> fields) {
  const Lattice& lattice = model.lattice;
  const bool plane = lattice.dim == 2;
  const std::int64_t bonds = lattice.bond_count();
  if (threads::used(lattice.node_count(), threads::node_grain) == 1) {
    for (std::int64_t b = 0; b < bonds; ++b) {
      if (!model.intact(b)) continue;
      const Bond& bond = lattice.bonds[b];
      const Vec3 arm_i = arm_at(lattice, b, bond.i, false),
                 arm_j = arm_at(lattice, b, bond.j, true);
      for (DyadSums* field : fields) {
        const Vec3 t = tension_of(model, b, *field);
        add_at_end(plane, *field, bond.i, arm_i, t, false);
        add_at_end(plane, *field, bond.j, arm_j, t, true);
      }
    }
    return;
  }
  std::vector<std::vector<Vec3>> tension(fields.size(), std::vector<Vec3>(bonds));
  threads::for_blocks(bonds, threads::bond_grain, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t b = first; b < last; ++b) {
      if (!model.intact(b)) continue;
      std::size_t f = 0;
      for (const DyadSums* field : fields) tension[f++][b] = tension_of(model, b, *field);
    }
  });
  const NodeBonds& index = model.node_bonds();
  threads::for_blocks(lattice.node_count(), threads::node_grain,
                      [&](std::int64_t first, std::int64_t last) {
                        for (std::int64_t n = first; n < last; ++n) {
                          for (std::int64_t k = index.start[n]; k < index.start[n + 1]; ++k) {
                            const std::int64_t b = index.entries[k] / 2;
                            if (!model.intact(b)) continue;
                            const bool end_j = index.entries[k] % 2 == 1;
                            const Vec3 arm = arm_at(lattice, b, n, end_j);
                            std::size_t f = 0;
                            for (DyadSums* field : fields)
                              add_at_end(plane, *field, n, arm, tension[f++][b], end_j);
                          }
                        }
                      });
}

// The Voigt stresses from one field's sums.
std::vector<double> voigt_stresses(const Model& model, DyadSums& field, bool with_loads) {
  const Lattice& lattice = model.lattice;
  if (!lattice.face_pieces.empty())
    add_support_dyads(model, field.bond_force, with_loads, field.sum);
  const std::vector<Mat3>& sum = field.sum;
  std::vector<double> voigt(lattice.node_count() * 6);
  const double scale = 1.0 / (2 * lattice.node_volume);
  for (std::int64_t n = 0; n < lattice.node_count(); ++n) {
    const double weight = lattice.is_random() ? 1.0 / lattice.node_volumes[n] : scale;
    const Mat3 s = 0.5 * weight * (sum[n] + sum[n].transpose());
    double* v = &voigt[n * 6];
    v[0] = s(0, 0);
    v[2] = s(2, 2);
    if (lattice.dim == 2) {
      // Plane strain: sigma_yy = nu (sigma_xx + sigma_zz) for what the lattice added; an
      // initial stress sigma0_v diag(K, K, 1) has its sigma_yy = K sigma0_v in full, so it
      // adds (K - nu (1 + K)) sigma0_v (K = 1: (1 - 2 nu) sigma0).
      const double nu = model.node_poisson[n];
      v[1] = nu * (s(0, 0) + s(2, 2));
      if (with_loads && model.has_prestress()) {
        const double k = model.initial_stress_ratio;
        v[1] += (k - nu * (1 + k)) * model.node_initial_stress[n];
      }
    } else {
      v[1] = s(1, 1);
    }
    v[3] = s(1, 2);
    v[4] = s(0, 2);
    v[5] = s(0, 1);
  }
  return voigt;
}

std::vector<double> stresses(const Model& model, const Vector& displacement, bool with_loads) {
  DyadSums field(model, displacement, with_loads, !model.lattice.face_pieces.empty());
  sum_dyads(model, {&field});
  return voigt_stresses(model, field, with_loads);
}

}  // namespace

std::vector<double> node_stresses(const Model& model, const Vector& displacement) {
  return stresses(model, displacement, true);
}

std::vector<double> node_stress_rates(const Model& model, const Vector& direction) {
  return stresses(model, direction, false);
}

NodeStressPath node_stress_path(const Model& model, const Vector& at_zero, const Vector& per_unit) {
  // One sweep for both fields: each field's sums take the same terms in the same order as
  // a sweep of its own, so the numbers are node_stresses' and node_stress_rates' exactly.
  const bool supports = !model.lattice.face_pieces.empty();
  DyadSums zero(model, at_zero, true, supports), rate(model, per_unit, false, supports);
  sum_dyads(model, {&zero, &rate});
  return {voigt_stresses(model, zero, true), voigt_stresses(model, rate, false)};
}

}  // namespace latfrac
