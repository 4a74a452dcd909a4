// Over-relaxed nodal Gauss-Seidel: the classical baseline equilibrium solver.
//
// Two implementations of the same sweep. A linear bond law's tension is its tangent
// times the relative displacement, so LinearNodes caches each active bond's tangent
// (from its interaction law) and each node's omega B^-1 once per solve, and a node visit is a few
// small matrix-vector products. Any other law goes through GeneralNodes, which asks the
// law for every bond's tension and tangent at each visit.
#include "latfrac/solvers/relaxation.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <string>

#include "latfrac/base/error.h"
#include "latfrac/base/phase_times.h"
#include "latfrac/base/stop_signal.h"

namespace latfrac {
namespace {

// The Vec3 axis of dof component c: x, z in 2-D; x, y, z in 3-D.
int axis_of(int dim, int c) { return dim == 2 ? 2 * c : c; }

// Does bond b contribute (a law acts on it in a state that is not open)?
bool acts(const Model& model, std::int64_t b) {
  return model.state(b) != PairState::open && model.law_of(b) != nullptr;
}

// Per node, bit a set when Vec3 axis a is a free degree of freedom.
std::vector<std::uint8_t> free_axes_of(const Model& model) {
  const int dim = model.dim();
  std::vector<std::uint8_t> free_axes(model.lattice.node_count(), 0);
  for (std::int64_t n = 0; n < model.lattice.node_count(); ++n) {
    for (int c = 0; c < dim; ++c) {
      if (model.dofs().free_index[n * dim + c] >= 0) free_axes[n] |= 1u << axis_of(dim, c);
    }
  }
  return free_axes;
}

// Bond b's tension (the internal force on its end j) and, when asked, its tangent.
Vec3 bond_tension(const Model& model, std::int64_t b, const Vec3& du, Mat3* tangent) {
  const InteractionLaw& law = *model.law_of(b);
  const PairSprings springs = model.springs(b);
  if (tangent) *tangent = law.tangent(springs, model.state(b), du);
  return law.tension(springs, model.state(b), du);
}

// A node's move per unit out-of-balance force: omega B^-1 on the free axes, zero rows and
// columns on the others. A singular B (a node held by too few pairs: one contact, say)
// takes its pseudo-inverse: the node moves only where it has stiffness, and each
// direction is relaxed once. (Relaxing each axis on its own, omega F_a / B_aa, relaxes a
// single inclined spring once per axis it touches: its misfit is multiplied by
// 1 - 2 omega per visit in 2-D, and the sweep diverges for omega > 1.) An axis without
// stiffness stays.
Mat3 update_operator(const Mat3& block, std::uint8_t free_axes, double omega) {
  double scale = 0;
  for (int a = 0; a < 3; ++a) {
    if (free_axes & (1u << a)) scale = std::max(scale, block(a, a));
  }
  Mat3 update = Mat3::Zero();
  if (scale <= 0) return update;
  // The free part of B, completed by scale * I on the held axes so that it can be inverted.
  Mat3 restricted = block;
  for (int a = 0; a < 3; ++a) {
    if (free_axes & (1u << a)) continue;
    restricted.row(a).setZero();
    restricted.col(a).setZero();
    restricted(a, a) = scale;
  }
  Mat3 inverse;
  double determinant = 0;
  bool invertible = false;
  restricted.computeInverseAndDetWithCheck(inverse, determinant, invertible,
                                           1e-10 * scale * scale * scale);
  if (!invertible) {
    // Tangent blocks are symmetric here (relaxation has no friction); their eigenvalues
    // below 1e-10 of the largest are taken as zero.
    const Eigen::SelfAdjointEigenSolver<Mat3> eigen(0.5 * (restricted + restricted.transpose()));
    const double largest = eigen.eigenvalues().cwiseAbs().maxCoeff();
    inverse.setZero();
    for (int k = 0; k < 3; ++k) {
      const double value = eigen.eigenvalues()[k];
      if (value > 1e-10 * largest)
        inverse += eigen.eigenvectors().col(k) * eigen.eigenvectors().col(k).transpose() / value;
    }
  }
  for (int a = 0; a < 3; ++a) {
    if (!(free_axes & (1u << a))) continue;
    for (int b = 0; b < 3; ++b) {
      if (free_axes & (1u << b)) update(a, b) = omega * inverse(a, b);
    }
  }
  return update;
}

// The sweep of a linear law in D = dim components, on cached couplings.
template <int D>
class LinearNodes {
 public:
  using VecD = Eigen::Matrix<double, D, 1>;
  using MatD = Eigen::Matrix<double, D, D>;

  LinearNodes(const Model& model, const NodeBonds& node_bonds, const Vector& displacement,
              double omega)
      : external_(model.external_force) {
    const std::int64_t nodes = model.lattice.node_count();
    const std::vector<std::uint8_t> free_axes = free_axes_of(model);
    first_.assign(nodes + 1, 0);
    update_.assign(nodes, MatD::Zero());
    free_.assign(nodes, VecD::Zero());
    for (std::int64_t n = 0; n < nodes; ++n) {
      first_[n + 1] = first_[n];
      if (!free_axes[n]) continue;
      Mat3 block = Mat3::Zero();
      for (std::int64_t k = node_bonds.start[n]; k < node_bonds.start[n + 1]; ++k) {
        const std::int64_t b = node_bonds.entries[k] / 2;
        if (!acts(model, b)) continue;
        const Bond& bond = model.lattice.bonds[b];
        Mat3 tangent;
        bond_tension(model, b, model.bond_displacement(displacement, b), &tangent);
        block += tangent;
        neighbour_.push_back(bond.i == n ? bond.j : bond.i);
        stiffness_.push_back(restrict(tangent));
        ++first_[n + 1];
      }
      update_[n] = restrict(update_operator(block, free_axes[n], omega));
      for (int c = 0; c < D; ++c) free_[n][c] = (free_axes[n] >> axis_of(D, c)) & 1u;
    }
  }

  void sweep(Vector& u) const {
    for (std::int64_t n = 0; n + 1 < static_cast<std::int64_t>(first_.size()); ++n) {
      if (free_[n].isZero()) continue;
      u.template segment<D>(n * D) += update_[n] * force(u, n);
    }
  }

  // Infinity when a force is not finite: std::max would skip a NaN.
  double max_force(const Vector& u) const {
    double largest = 0;
    for (std::int64_t n = 0; n + 1 < static_cast<std::int64_t>(first_.size()); ++n) {
      if (free_[n].isZero()) continue;
      const auto f = force(u, n).cwiseProduct(free_[n]).eval();
      if (!f.allFinite()) return std::numeric_limits<double>::infinity();
      largest = std::max(largest, f.cwiseAbs().maxCoeff());
    }
    return largest;
  }

 private:
  static MatD restrict(const Mat3& m) {
    MatD r;
    for (int row = 0; row < D; ++row) {
      for (int col = 0; col < D; ++col) r(row, col) = m(axis_of(D, row), axis_of(D, col));
    }
    return r;
  }

  // External minus internal force on node n: every coupling pulls by K (u_n - u_neighbour).
  VecD force(const Vector& u, std::int64_t n) const {
    const VecD own = u.template segment<D>(n * D);
    VecD f = external_.template segment<D>(n * D);
    for (std::int64_t k = first_[n]; k < first_[n + 1]; ++k) {
      f.noalias() -= stiffness_[k] * (own - u.template segment<D>(neighbour_[k] * D));
    }
    return f;
  }

  const Vector& external_;
  std::vector<std::int64_t> first_;  // node n's couplings: [first_[n], first_[n + 1])
  std::vector<std::int64_t> neighbour_;
  std::vector<MatD> stiffness_;  // the bond's tangent, on the dof components
  std::vector<MatD> update_;     // per node: omega B^-1, zero on held components
  std::vector<VecD> free_;       // per node: 1 on free components, 0 on held ones
};

// The sweep of any bond law: tension and tangent from the law at every visit.
class GeneralNodes {
 public:
  GeneralNodes(const Model& model, const NodeBonds& node_bonds, double omega)
      : model_(model), node_bonds_(node_bonds), omega_(omega), free_axes_(free_axes_of(model)) {
    acts_.resize(model.lattice.bond_count());
    for (std::int64_t b = 0; b < model.lattice.bond_count(); ++b) acts_[b] = acts(model, b);
  }

  void sweep(Vector& u) const {
    const int dim = model_.dim();
    Mat3 block;
    for (std::int64_t n = 0; n < model_.lattice.node_count(); ++n) {
      if (!free_axes_[n]) continue;
      const Vec3 f = force(u, n, &block);
      const Vec3 move = update_operator(block, free_axes_[n], omega_) * f;
      for (int c = 0; c < dim; ++c) u[n * dim + c] += move[axis_of(dim, c)];
    }
  }

  double max_force(const Vector& u) const {
    double largest = 0;
    for (std::int64_t n = 0; n < model_.lattice.node_count(); ++n) {
      if (!free_axes_[n]) continue;
      const Vec3 f = force(u, n, nullptr);
      for (int a = 0; a < 3; ++a) {
        if (!(free_axes_[n] & (1u << a))) continue;
        if (!std::isfinite(f[a])) return std::numeric_limits<double>::infinity();
        largest = std::max(largest, std::abs(f[a]));
      }
    }
    return largest;
  }

 private:
  // External minus internal force on node n from its own bonds, and its stiffness block.
  Vec3 force(const Vector& u, std::int64_t n, Mat3* block) const {
    Vec3 f = model_.node_displacement(model_.external_force, n);
    if (block) block->setZero();
    Mat3 tangent;
    for (std::int64_t k = node_bonds_.start[n]; k < node_bonds_.start[n + 1]; ++k) {
      const std::int64_t b = node_bonds_.entries[k] / 2;
      if (!acts_[b]) continue;
      const Vec3 t =
          bond_tension(model_, b, model_.bond_displacement(u, b), block ? &tangent : nullptr);
      if (block) *block += tangent;
      // The internal force is +t on end j and -t on end i.
      if (model_.lattice.bonds[b].j == n) {
        f -= t;
      } else {
        f += t;
      }
    }
    return f;
  }

  const Model& model_;
  const NodeBonds& node_bonds_;
  double omega_;
  std::vector<std::uint8_t> free_axes_;
  std::vector<std::uint8_t> acts_;  // per bond: acts() when the solve started
};

// Sweeps until the relative residual meets the tolerance or the sweeps run out.
template <typename Nodes>
RelaxationReport iterate(const Nodes& nodes, Vector& u, double load, double tolerance,
                         long max_sweeps, long check_interval) {
  RelaxationReport report;
  report.relative_residual = nodes.max_force(u) / load;
  while (report.relative_residual > tolerance && report.sweeps < max_sweeps) {
    nodes.sweep(u);
    ++report.sweeps;
    if (report.sweeps % check_interval == 0 || report.sweeps == max_sweeps) {
      report.relative_residual = nodes.max_force(u) / load;
      // A diverging iteration (a nonlinear law far from equilibrium) stops here.
      if (!std::isfinite(report.relative_residual)) break;
      // So does a run asked to stop: a solve can take minutes of sweeps.
      if (stop_requested()) throw StopWithinEvent();
    }
  }
  report.converged = report.relative_residual <= tolerance;
  return report;
}

}  // namespace

RelaxationSolver::RelaxationSolver(const SolverOptions& options)
    : omega_(options.relaxation_omega),
      tolerance_(options.relaxation_tolerance),
      max_sweeps_(options.relaxation_max_sweeps) {
  if (!(omega_ > 0 && omega_ < 2)) {
    throw InputError("relaxation_omega = " + std::to_string(omega_) +
                     ": allowed: 0 < relaxation_omega < 2");
  }
  if (!(tolerance_ > 0)) {
    throw InputError("relaxation_tolerance = " + std::to_string(tolerance_) +
                     ": allowed: relaxation_tolerance > 0");
  }
  if (max_sweeps_ < 0) {
    throw InputError("relaxation_max_sweeps = " + std::to_string(max_sweeps_) +
                     ": allowed: relaxation_max_sweeps >= 0");
  }
}

RelaxationReport RelaxationSolver::solve(const Model& model, double lambda,
                                         Vector& free_displacement) const {
  const ScopedPhase phase(Phase::solve);
  const std::int64_t free_count = model.dofs().free_count;
  assert(free_displacement.size() == free_count);
  const double load = max_abs(model.residual(Vector::Zero(free_count), lambda));
  if (free_count == 0 || load == 0) {
    free_displacement.setZero(free_count);
    RelaxationReport report;
    report.converged = true;
    return report;
  }

  Vector u = model.full_displacement(free_displacement, lambda);
  RelaxationReport report;
  if (model.is_linear() && model.dim() == 2) {
    const LinearNodes<2> nodes(model, model.node_bonds(), u, omega_);
    report = iterate(nodes, u, load, tolerance_, max_sweeps_, check_interval);
  } else if (model.is_linear()) {
    const LinearNodes<3> nodes(model, model.node_bonds(), u, omega_);
    report = iterate(nodes, u, load, tolerance_, max_sweeps_, check_interval);
  } else {
    const GeneralNodes nodes(model, model.node_bonds(), omega_);
    report = iterate(nodes, u, load, tolerance_, max_sweeps_, check_interval);
  }

  for (std::int64_t dof = 0; dof < model.dofs().dof_count(); ++dof) {
    const std::int64_t f = model.dofs().free_index[dof];
    if (f >= 0) free_displacement[f] = u[dof];
  }
  return report;
}

}  // namespace latfrac
