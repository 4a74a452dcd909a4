// Virial node stresses: the branch form on regular lattices, the facet-centroid form on
// random ones.
#include "latfrac/mechanics/node_stress.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <utility>
#include <vector>

#include "latfrac/base/error.h"
#include "latfrac/base/phase_times.h"
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

// The supports' forces on a random lattice's face node `node`, whose pieces are
// pieces[first, last): a held component's force is what balances the node's intact bonds
// (`bond_force`, their force on the node) and, with the loads, its weight. It goes to the
// piece whose normal is that axis, or else (a base held along x under a basal
// discontinuity) to the node's first. Then the overburden's pressure on its top face
// pieces, at their centroids (a held z is a support's, counted before).
void add_node_support_dyads(const Model& model, std::size_t first, std::size_t last,
                            const Vec3& bond_force, bool with_loads, Mat3& sum) {
  const Lattice& lattice = model.lattice;
  const int dim = lattice.dim;
  const std::vector<int> axes = lattice.axes();
  const auto& pieces = lattice.face_pieces;
  const std::int64_t node = pieces[first].node;
  for (int c = 0; c < dim; ++c) {
    const std::int64_t dof = node * dim + c;
    if (model.dofs().free_index[dof] >= 0) continue;
    const int axis = axes[c];
    double support = -bond_force[axis];
    if (with_loads) support -= model.external_force[dof];
    const FacePiece* piece = &pieces[first];
    for (std::size_t k = first; k < last; ++k)
      if (pieces[k].axis == axis) piece = &pieces[k];
    add_dyad(dim == 2, sum, piece->arm, support * Vec3::Unit(axis));
  }
  if (!with_loads || model.top_pressure == 0) return;
  if (model.dofs().free_index[node * dim + (dim - 1)] < 0) return;
  for (std::size_t k = first; k < last; ++k)
    if (lattice.on_top(pieces[k]))
      add_dyad(dim == 2, sum, pieces[k].arm, -model.top_pressure * pieces[k].area * Vec3::UnitZ());
}

// The end of node `first`'s run of face pieces (they are in node order).
std::size_t pieces_end(const std::vector<FacePiece>& pieces, std::size_t first) {
  std::size_t last = first;
  while (last < pieces.size() && pieces[last].node == pieces[first].node) ++last;
  return last;
}

// Node n's first face piece (they are in node order), or pieces.size() when it has none.
std::size_t first_piece(const std::vector<FacePiece>& pieces, std::int64_t n) {
  const auto first = static_cast<std::size_t>(
      std::lower_bound(pieces.begin(), pieces.end(), n,
                       [](const FacePiece& p, std::int64_t node) { return p.node < node; }) -
      pieces.begin());
  return first < pieces.size() && pieces[first].node == n ? first : pieces.size();
}

// The supports' dyads of every face node (add_node_support_dyads).
void add_support_dyads(const Model& model, const std::vector<Vec3>& bond_force, bool with_loads,
                       std::vector<Mat3>& sum) {
  const auto& pieces = model.lattice.face_pieces;
  for (std::size_t first = 0; first < pieces.size();) {
    const std::size_t last = pieces_end(pieces, first);
    const std::int64_t node = pieces[first].node;
    add_node_support_dyads(model, first, last, bond_force[node], with_loads, sum[node]);
    first = last;
  }
}

// What a sweep over the bonds sums for one displacement field: per node, the sum over
// its intact bonds of arm (x) force, and on a random lattice with face pieces each node's
// force from its intact bonds (for the supports). A rate (`state` false) reads u_j - u_i
// alone: the bonds' prestretch is part of the state. The sums are filled by the sweep
// (every node's, zero where it has no intact bond).
struct DyadSums {
  DyadSums(const Model& model, const Vector& u, bool state_field, bool with_force)
      : displacement(u),
        state(state_field),
        sum(model.lattice.node_count()),
        bond_force(with_force ? model.lattice.node_count() : 0) {}
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

// Adds a bond's tension t at one of its ends to that node's sums.
void add_at_end(bool plane, Mat3& sum, Vec3* force, const Vec3& arm, const Vec3& t, bool end_j) {
  add_dyad(plane, sum, arm, t);
  if (!force) return;
  if (end_j) {
    *force -= t;
  } else {
    *force += t;
  }
}

// Bond b's tension under `law` (the model's bond law, as its own type or as a BondLaw).
template <class Law>
Vec3 tension_of(const Law& law, const Model& model, std::int64_t b, const Vector& displacement,
                bool state) {
  const Vec3 du =
      state ? model.bond_displacement(displacement, b) : model.relative_motion(displacement, b);
  return law.tension(model.springs(b), PairState::intact, du);
}

// Calls body(law) with the model's bond law: as a SmallKinematics where it is one (a final
// class, so its tension is called inline in the sweep), else as a BondLaw. The same
// function computes each tension either way.
template <class Body>
void with_bond_law(const Model& model, const Body& body) {
  if (const auto* small = dynamic_cast<const SmallKinematics*>(&model.bond_law())) {
    body(*small);
  } else {
    body(model.bond_law());
  }
}

// One node's sums over its intact bonds in bond order, the tension of bond b for field f
// given by tension(f, b). The same terms in the same order as a loop over all bonds that
// adds each bond to its two ends, so the same numbers.
template <class Tension>
void node_sums(const Model& model, const NodeBonds& index, std::int64_t n, std::size_t fields,
               Mat3* sum, Vec3* force, const Tension& tension) {
  const Lattice& lattice = model.lattice;
  const bool plane = lattice.dim == 2;
  for (std::size_t f = 0; f < fields; ++f) {
    sum[f].setZero();
    if (force) force[f].setZero();
  }
  for (std::int64_t k = index.start[n]; k < index.start[n + 1]; ++k) {
    const std::int64_t b = index.entries[k] / 2;
    if (!model.intact(b)) continue;
    const bool end_j = index.entries[k] % 2 == 1;
    const Vec3 arm = arm_at(lattice, b, n, end_j);
    for (std::size_t f = 0; f < fields; ++f)
      add_at_end(plane, sum[f], force ? &force[f] : nullptr, arm, tension(f, b), end_j);
  }
}

// Sums the dyads of every intact bond into each field (at most two). In 2-D only the
// x-z block is summed: the y row and column stay zero. On one thread: one loop over the
// bonds, each added to its two ends. On more: the bonds' tensions (each bond on its own),
// then each node's sum over its bonds in bond order (node_sums): the same numbers on any
// number of threads.
void sum_dyads(const Model& model, std::initializer_list<DyadSums*> fields) {
  const Lattice& lattice = model.lattice;
  const bool plane = lattice.dim == 2;
  const std::int64_t bonds = lattice.bond_count();
  const std::vector<DyadSums*> field(fields);
  const std::size_t count = field.size();
  if (count > 2) throw Error("sum_dyads: at most two fields");
  if (threads::used(lattice.node_count(), threads::node_grain) == 1) {
    for (DyadSums* f : field) {
      std::fill(f->sum.begin(), f->sum.end(), Mat3::Zero());
      std::fill(f->bond_force.begin(), f->bond_force.end(), Vec3::Zero());
    }
    with_bond_law(model, [&](const auto& law) {
      for (std::int64_t b = 0; b < bonds; ++b) {
        if (!model.intact(b)) continue;
        const Bond& bond = lattice.bonds[b];
        const Vec3 arm_i = arm_at(lattice, b, bond.i, false),
                   arm_j = arm_at(lattice, b, bond.j, true);
        for (DyadSums* f : field) {
          const Vec3 t = tension_of(law, model, b, f->displacement, f->state);
          const bool forces = !f->bond_force.empty();
          add_at_end(plane, f->sum[bond.i], forces ? &f->bond_force[bond.i] : nullptr, arm_i, t,
                     false);
          add_at_end(plane, f->sum[bond.j], forces ? &f->bond_force[bond.j] : nullptr, arm_j, t,
                     true);
        }
      }
    });
    return;
  }
  // The fields' tensions of one bond side by side: the node sums read them together.
  std::vector<Vec3> tension(count * static_cast<std::size_t>(bonds));
  with_bond_law(model, [&](const auto& law) {
    threads::for_blocks(bonds, threads::bond_grain, [&](std::int64_t first, std::int64_t last) {
      for (std::int64_t b = first; b < last; ++b) {
        if (!model.intact(b)) continue;
        for (std::size_t f = 0; f < count; ++f)
          tension[static_cast<std::size_t>(b) * count + f] =
              tension_of(law, model, b, field[f]->displacement, field[f]->state);
      }
    });
  });
  const NodeBonds& index = model.node_bonds();
  const bool forces = !field[0]->bond_force.empty();
  threads::for_blocks(
      lattice.node_count(), threads::node_grain, [&](std::int64_t first, std::int64_t last) {
        Mat3 sum[2];
        Vec3 force[2];
        for (std::int64_t n = first; n < last; ++n) {
          node_sums(model, index, n, count, sum, forces ? force : nullptr,
                    [&](std::size_t f, std::int64_t b) -> const Vec3& {
                      return tension[static_cast<std::size_t>(b) * count + f];
                    });
          for (std::size_t f = 0; f < count; ++f) {
            field[f]->sum[n] = sum[f];
            if (forces) field[f]->bond_force[n] = force[f];
          }
        }
      });
}

// Node n's Voigt stress from its sum of dyads.
void voigt_of(const Model& model, std::int64_t n, const Mat3& sum, bool with_loads, double* v) {
  const Lattice& lattice = model.lattice;
  const double scale = 1.0 / (2 * lattice.node_volume);
  const double weight = lattice.is_random() ? 1.0 / lattice.node_volumes[n] : scale;
  const Mat3 s = 0.5 * weight * (sum + sum.transpose());
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

// The Voigt stresses from one field's sums.
std::vector<double> voigt_stresses(const Model& model, DyadSums& field, bool with_loads) {
  const Lattice& lattice = model.lattice;
  if (!lattice.face_pieces.empty())
    add_support_dyads(model, field.bond_force, with_loads, field.sum);
  std::vector<double> voigt(lattice.node_count() * 6);
  for (std::int64_t n = 0; n < lattice.node_count(); ++n)
    voigt_of(model, n, field.sum[n], with_loads, &voigt[n * 6]);
  return voigt;
}

// The listed nodes' Voigt stresses for each field (its displacement, and whether it is a
// state, read with the loads, or a rate), each summed over the node's own bonds: the
// sweep's numbers bit for bit. The other nodes' entries are NaN.
std::vector<std::vector<double>> stresses_at(
    const Model& model, const std::vector<std::int64_t>& nodes,
    std::initializer_list<std::pair<const Vector*, bool>> fields) {
  const std::vector<std::pair<const Vector*, bool>> field(fields);
  const std::size_t count = field.size();
  if (count > 2) throw Error("stresses_at: at most two fields");
  const Lattice& lattice = model.lattice;
  std::vector<std::vector<double>> voigt(
      count,
      std::vector<double>(lattice.node_count() * 6, std::numeric_limits<double>::quiet_NaN()));
  const NodeBonds& index = model.node_bonds();
  const auto& pieces = lattice.face_pieces;
  with_bond_law(model, [&](const auto& law) {
    for (const std::int64_t n : nodes) {
      Mat3 sum[2];
      Vec3 force[2];
      node_sums(model, index, n, count, sum, pieces.empty() ? nullptr : force,
                [&](std::size_t f, std::int64_t b) {
                  return tension_of(law, model, b, *field[f].first, field[f].second);
                });
      const std::size_t first = first_piece(pieces, n);
      for (std::size_t f = 0; f < count; ++f) {
        if (first < pieces.size())
          add_node_support_dyads(model, first, pieces_end(pieces, first), force[f], field[f].second,
                                 sum[f]);
        voigt_of(model, n, sum[f], field[f].second, &voigt[f][n * 6]);
      }
    }
  });
  return voigt;
}

std::vector<double> stresses(const Model& model, const Vector& displacement, bool with_loads) {
  DyadSums field(model, displacement, with_loads, !model.lattice.face_pieces.empty());
  sum_dyads(model, {&field});
  return voigt_stresses(model, field, with_loads);
}

}  // namespace

std::vector<double> node_stresses(const Model& model, const Vector& displacement) {
  const ScopedPhase phase(Phase::node_stress);
  return stresses(model, displacement, true);
}

std::vector<double> node_stresses_at(const Model& model, const Vector& displacement,
                                     const std::vector<std::int64_t>& nodes) {
  const ScopedPhase phase(Phase::node_stress);
  return std::move(stresses_at(model, nodes, {{&displacement, true}}).front());
}

std::vector<double> node_stress_rates(const Model& model, const Vector& direction) {
  const ScopedPhase phase(Phase::node_stress);
  return stresses(model, direction, false);
}

NodeStressPath node_stress_path_at(const Model& model, const Vector& at_zero,
                                   const Vector& per_unit, const std::vector<std::int64_t>& nodes) {
  const ScopedPhase phase(Phase::node_stress);
  std::vector<std::vector<double>> both =
      stresses_at(model, nodes, {{&at_zero, true}, {&per_unit, false}});
  return {std::move(both[0]), std::move(both[1])};
}

std::vector<double> node_stress_bounds(const Model& model) {
  const Lattice& lattice = model.lattice;
  const int dim = lattice.dim;
  // |du| <= 2 sqrt(dim) max|u| for a bond's relative displacement; |t| <= max(kn, ks) |du|.
  const double relative = 2 * std::sqrt(static_cast<double>(dim));
  std::vector<double> arms(lattice.node_count(), 0.0), forces(lattice.node_count(), 0.0);
  for (std::int64_t b = 0; b < lattice.bond_count(); ++b) {
    const Bond& bond = lattice.bonds[b];
    const PairSprings springs = model.springs(b);
    const double stiffness = relative * std::max(std::abs(springs.kn), std::abs(springs.ks));
    arms[bond.i] += arm_at(lattice, b, bond.i, false).norm() * stiffness;
    arms[bond.j] += arm_at(lattice, b, bond.j, true).norm() * stiffness;
    forces[bond.i] += stiffness;
    forces[bond.j] += stiffness;
  }
  // A face node's supports: each of its components, if held, balances its bonds' forces
  // (at most the sum of their sizes) on the arm of one of its pieces.
  std::vector<double> piece_arm(lattice.node_count(), 0.0);
  for (const FacePiece& piece : lattice.face_pieces)
    piece_arm[piece.node] = std::max(piece_arm[piece.node], piece.arm.norm());
  std::vector<double> bound(lattice.node_count());
  const double scale = 1.0 / (2 * lattice.node_volume);
  for (std::int64_t n = 0; n < lattice.node_count(); ++n) {
    const double weight = lattice.is_random() ? 1.0 / lattice.node_volumes[n] : scale;
    bound[n] = weight * (arms[n] + dim * piece_arm[n] * forces[n]);
  }
  return bound;
}

NodeStressPath node_stress_path(const Model& model, const Vector& at_zero, const Vector& per_unit) {
  const ScopedPhase phase(Phase::node_stress);
  // One sweep for both fields: each field's sums take the same terms in the same order as
  // a sweep of its own, so the numbers are node_stresses' and node_stress_rates' exactly.
  const bool supports = !model.lattice.face_pieces.empty();
  DyadSums zero(model, at_zero, true, supports), rate(model, per_unit, false, supports);
  sum_dyads(model, {&zero, &rate});
  return {voigt_stresses(model, zero, true), voigt_stresses(model, rate, false)};
}

}  // namespace latfrac
