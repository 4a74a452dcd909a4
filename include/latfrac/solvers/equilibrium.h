// Static equilibrium R(u, lambda) = 0 by KINSOL's Newton iteration on a CHOLMOD factor.
//
// The unknowns are the free displacements; R is the out-of-balance force (internal minus
// external) on them, and its Jacobian is the tangent stiffness K. KINSOL drives the
// iteration; its linear solver is our own SUNLinearSolver whose setup factorizes K with
// CHOLMOD (symbolic analysis reused) and whose solve back-substitutes. The stopping test
// is max |R| <= tolerance * max |R(0, lambda)|: the residual relative to the load.
//
// With a linear bond law and a fixed set of intact bonds the path is affine,
// u(lambda) = u_g + lambda u_e; affine_path() factorizes once and solves the gravity and
// the unit-extension right-hand sides together.
#pragma once

#include <Eigen/LU>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "latfrac/mechanics/model.h"
#include "latfrac/mechanics/stiffness.h"
#include "latfrac/solvers/linear_backend.h"
#include "latfrac/solvers/solver_options.h"

namespace latfrac {

struct EquilibriumReport {
  long newton_iterations = 0;
  long residual_evaluations = 0;
  double relative_residual = 0;  // max |R| / max |R(0, lambda)|
};

// Free displacements along an affine path: u(lambda) = gravity + lambda * extension.
struct AffinePath {
  Vector gravity;
  Vector extension;
  Vector at(double lambda) const { return gravity + lambda * extension; }
};

struct SolverCounters {
  long solves = 0;          // back-substitutions with the factor (each may hold several RHS)
  long coupled_solves = 0;  // of the solves: with slipping contacts (solve_coupled)
  long factorizations = 0;  // numeric factorizations
  long factor_updates = 0;  // rank updates of the factor
  long correction_solves = 0;  // of the solves: few-entry corrections (checked_solve)
  // Solutions accepted at the rounding floor with a residual above solver.tolerance
  // (within max_rounding_excess of it; docs/robustness.md).
  long floor_acceptances = 0;
};

class EquilibriumSolver {
 public:
  EquilibriumSolver(Model& model, const SolverOptions& options);
  ~EquilibriumSolver();
  EquilibriumSolver(const EquilibriumSolver&) = delete;
  EquilibriumSolver& operator=(const EquilibriumSolver&) = delete;

  // Newton from the given free displacement (updated in place) at extension strain lambda.
  // Throws Error naming the KINSOL or CHOLMOD call when it fails.
  EquilibriumReport solve(double lambda, Vector& free_displacement);

  // Requires a linear bond law. One factorization, one two-column solve.
  AffinePath affine_path();

  // The only way a run changes the model (ModelEditor), so that the factor follows:
  //
  // Puts pair b into `state` and updates the factor: the rank-1 terms of the old state's
  // law come out (rank 2 in 2-D, 3 in 3-D for an intact bond; 1 for a closed contact),
  // those of the new state's go in. A fresh factorization replaces the updates after
  // refactor_every of them.
  void set_pair_state(std::int64_t bond, PairState state);
  // Sets a frictional contact's memory (its anchor is a load while it sticks).
  void set_contact_memory(std::int64_t bond, const ContactMemory& memory);
  // The normal an intact bond's contact will act along once it breaks (contacts along
  // cracks): no factor holds it yet, so nothing else changes.
  void set_contact_normal(std::int64_t bond, const Vec3& normal) {
    editor_.set_contact_normal(bond, normal);
  }
  // Holds the given nodes along the given components at the full displacement (their free
  // dofs become prescribed, rate 0); rebuilds the stiffness pattern and its analysis.
  struct Hold {
    std::vector<std::int64_t> nodes;
    std::vector<int> components;
  };
  void hold(const std::vector<Hold>& holds, const Vector& displacement);
  // Drops the factor: the next solve assembles and factorizes afresh (benchmarks time it).
  void discard_factor() {
    factor_current_ = false;
    last_solution_valid_ = false;
  }

  // The affine path of the current stiffness, its residual checked at lambda: when the
  // updated factor's answer misses the tolerance, refactorizes and solves again.
  AffinePath checked_affine_path(double lambda);
  // The free displacement at lambda alone (one right-hand side), checked the same way:
  // what a cascade at fixed lambda needs after each break.
  Vector checked_solve(double lambda);


  // max |R(0, lambda)|: the size of the load at lambda, N.
  double load_scale(double lambda);

  // How the factor came about and the last checked solution: what a resumed run needs to
  // rebuild the factor bit for bit (a fresh factorization rounds differently from one
  // that was updated, and a long run would drift apart; docs/restart.md).
  struct History {
    bool factor_current = false;
    std::vector<std::uint8_t> factored_states;  // pair states at the last factorization
    std::vector<std::pair<std::int64_t, std::uint8_t>> changes;  // set_pair_state since
    bool solution_valid = false;
    double solution_lambda = 0;
    Vector solution;
    LinearBackend::Column pending_forces;
    // The order the last analysis was given (free numbering; empty: the ordering method
    // chose it). Holds inherit the order (supports_changed), so the resumed supports,
    // ordered afresh, would round differently; analysing with the same input again gives
    // the same analysis.
    std::vector<std::int64_t> elimination_order;
    // With friction, the LU of the nonsymmetric stiffness the same way: the pair states
    // and senses of slip (3 per bond) it was factorized for, and the pairs changed since
    // with their Jacobian's change (bond, then 9 values row by row).
    bool lu_current = false;
    std::vector<std::uint8_t> lu_states;
    std::vector<double> lu_directions;
    std::vector<std::int64_t> lu_change_bonds;
    std::vector<double> lu_change_values;
    // With friction, the Woodbury terms of the slipping contacts as the run carried them
    // along (empty: none kept): their bonds, the number of values of each one's coupling
    // terms and those values (7 per term: weight, left, right), W (free dofs x bonds,
    // column by column), and the factor updates W has not followed yet: how many, and
    // their columns (column c's entries are pending_index/value from pending_start[c] to
    // pending_start[c + 1]) with their signs. Solved afresh, W would round differently
    // from the columns the factor updates carried along.
    std::vector<std::int64_t> woodbury_bonds;
    std::vector<std::int64_t> woodbury_term_counts;
    std::vector<double> woodbury_terms;
    std::vector<double> woodbury_w;
    std::int64_t woodbury_pending_updates = 0;
    std::vector<std::int64_t> woodbury_pending_start;
    std::vector<std::int64_t> woodbury_pending_index;
    std::vector<double> woodbury_pending_value;
    std::vector<double> woodbury_pending_sign;
    // The affine path's Y = A^-1 [load0 load1] as the run carried it along (empty: none
    // kept), free dofs x 2 column by column, and the loads it solves (load0 then load1).
    // The pending updates above are Y's too (and written when only Y is kept).
    std::vector<double> path_y;
    std::vector<double> path_loads;
  };
  History history() const;
  // With the model in history.factored_states (when the factor was current) and in its
  // present supports: factorizes, replays the changes and takes the last solution back,
  // and leaves the model in `states`. The counters start again from zero.
  void rebuild(const History& history, const std::vector<PairState>& states);
  void rebuild_lu(const History& history);
  // W, Y and the pending updates (followed_solves) as the run had carried them.
  void rebuild_followed(const History& history);

  const SolverCounters& counters() const { return counters_; }
  StiffnessMatrix& stiffness() { return stiffness_; }
  LinearBackend& factor() { return *factor_; }

 private:
  struct Kinsol;  // equilibrium_newton.cpp
  friend struct Kinsol;
  void reset_kinsol();
  // The model's supports changed: rebuilds the stiffness pattern, the analysis and
  // KINSOL's memory.
  void supports_changed();
  // The last analysis's elimination order restricted to the dofs still free, in the new
  // numbering; empty (order afresh) on the first analysis or when a dof became free.
  std::vector<std::int64_t> inherited_order() const;
  // Analyses the stiffness pattern with `given` (empty: the ordering method) and records
  // which dof each free index is, for the next inherited_order().
  void analyse(const std::vector<std::int64_t>& given);
  std::vector<std::int64_t> analysed_globals_;  // free index -> global dof at the last analysis
  void refactorize(const Vector& free_displacement, double lambda);
  // The loads on the free dofs at zero free displacement: load0 (gravity and the fixed
  // part of the supports) and load1 (per unit lambda), so that R(0, lambda) = -(load0 +
  // lambda load1). Only bonds that touch a prescribed dof contribute: the others are
  // unstretched when every free dof is zero.
  void update_loads();
  void find_boundary_bonds();
  std::vector<std::int64_t> boundary_bonds_;
  std::vector<std::uint8_t> on_boundary_;  // per bond: in boundary_bonds_
  Vector load0_, load1_;
  bool loads_current_ = false;
  // The relative residual of a free displacement at lambda, max |R| / max |R(0, lambda)|.
  double relative_residual(const Vector& free_displacement, double lambda);
  // After a fresh factorization's solve missed the tolerance: throws SingularStiffness at a
  // near-mechanism, returns when the residual is at the rounding floor, throws Error else.
  void fresh_solve_missed(const Vector& free_displacement, double lambda, double residual);
  bool at_rounding_floor(const Vector& free_displacement, double lambda);
  // A miss that no solve can improve on, and so accepted: a relative residual within
  // max_rounding_excess of the tolerance, at the rounding floor. Counts each acceptance
  // (SolverCounters::floor_acceptances): its callers take the solution when it is true.
  bool accepted_at_floor(const Vector& free_displacement, double lambda, double residual);
  static constexpr double max_rounding_excess = 100;
  std::string ill_conditioned(const Vector& free_displacement, double lambda,
                              double residual) const;
  std::string describe_unknown(std::int64_t unknown) const;
  // Solves K x = rhs in place (n x columns) (coupled_solve.cpp): the factor's solve, and,
  // while contacts slip, with their nonsymmetric parts K = A + U V' (A the factor's
  // matrix; one column of U and V per slipping contact): up to woodbury_limit slipping
  // contacts, the Sherman-Morrison-Woodbury correction x = y - W (I + V' W)^-1 V' y with
  // y = A^-1 rhs and W = A^-1 U (kept along the factor updates: FollowedSolves); beyond,
  // an LU of K (UMFPACK), whose cost does not grow with their number. The limit was 16
  // while W was solved afresh after every update; following W made the Woodbury route
  // cheaper than the LU up to about a hundred (docs/benchmarks.md).
  void solve_coupled(double* rhs, std::int64_t n, int columns);
  static constexpr std::size_t woodbury_limit = 128;
  // The LU (coupled_solve.cpp): analysed once per set of supports (the pattern of every
  // bond's blocks). Like the Cholesky factor it is not redone at every change: the pairs
  // that changed since it was factorized (state, or sense of slip) are kept as their
  // Jacobian's change dJ, and the solves correct the LU's answer by Woodbury for them
  // (dim columns each; W = LU^-1 U grows by those columns only); past lu_update_limit
  // columns, or when lu_current_ is false (new supports, a fresh Cholesky factor after a
  // missed residual), the LU is factorized afresh.
  struct Unsymmetric;
  std::unique_ptr<Unsymmetric> unsymmetric_;
  bool lu_current_ = false;
  static constexpr Eigen::Index lu_update_limit = 64;
  std::vector<std::pair<std::int64_t, Mat3>> lu_changes_;
  std::size_t lu_changes_solved_ = 0;  // of lu_changes_: those with columns in lu_w_
  Eigen::MatrixXd lu_w_;
  std::vector<LinearBackend::Column> lu_v_;
  // The pair's exact tangent dt/d(du) in its state (zero without a law).
  Mat3 pair_jacobian(std::int64_t bond) const;
  // Records the change of bond's Jacobian from `before`, while an LU is current.
  void note_lu_change(std::int64_t bond, const Mat3& before);
  // The sliding contacts, in bond order (none without friction).
  std::vector<std::int64_t> slipping_pairs() const;
  // The motion that the slipping contacts leave (nearly) free, on a fresh factor: the
  // capacitance's smallest singular value over its largest, and the unknown the motion
  // moves most.
  struct SlidingMotion {
    double ratio = 1;
    Eigen::Index largest = -1;
  };
  SlidingMotion sliding_motion(const std::vector<std::int64_t>& slipping, std::int64_t n);
  // Below this ratio a missed residual is blamed on a part that slides nearly freely.
  static constexpr double sliding_mechanism_ratio = 1e-8;
  void woodbury_correction(const std::vector<std::int64_t>& slipping, double* rhs,
                           std::int64_t n, int columns);
  // Solves with the factor alone that are kept along its updates: the Woodbury
  // correction's W = A^-1 U (with V and the LU of I + V' W) while the slipping contacts'
  // coupling terms stay the same, and the affine path's Y = A^-1 [load0 load1] for the
  // loads it was solved with. A run solves several times between two changes (the
  // check, the path's two columns, the settling), and the factor changes by a rank update
  // or two between two paths. The factor updates since the solves were exact (A' = A +
  // C S C', S = +-1 per column) are kept, and the solves are brought to the new factor
  // when next needed: X' = X - A'^-1 C S C' X (exact: A' X' = A X), one solve with C's
  // few-entry columns for all of them, not one per column of W and Y. A contact that
  // starts slipping adds its column, solved alone; loads that changed (a stick contact's
  // anchor) add A^-1 of their change, which has a few entries too.
  struct FollowedSolves {
    std::uint64_t factor_version = 0;  // the factor the solves belong to
    std::vector<std::int64_t> bonds;   // W: each column's slipping contact (none: no columns)
    std::vector<std::vector<double>> terms;  // each column's coupling term, flattened
    Eigen::MatrixXd w;
    std::vector<LinearBackend::Column> v;
    Eigen::PartialPivLU<Eigen::MatrixXd> capacitance;
    Eigen::MatrixXd y;  // the path's Y (no columns: none kept)
    Vector y_load0, y_load1;  // the loads Y solves
    std::int64_t pending_updates = 0;  // factor updates since factor_version
    std::vector<LinearBackend::Column> pending;  // their columns C
    std::vector<double> pending_sign;           // S
    bool valid = false;
  };
  FollowedSolves followed_;
  // The followed solves brought to the factor, W for these slipping contacts (a column per
  // coupling term; its columns kept where the terms are the same, the others solved) and,
  // with_path, Y for the present loads.
  const FollowedSolves& followed_solves(const std::vector<std::int64_t>& pairs, std::int64_t n,
                                        bool with_path);
  // The factor was just updated by +- C C' (`columns`): the followed solves keep C for
  // later, or are dropped when they do not belong to the factor just before, or when C
  // has grown to as many columns as W and to more than 4 (one pass over the factor; then
  // solved afresh they cost no more).
  void follow_factor_update(const std::vector<LinearBackend::Column>& columns, bool downdate);
  // V and the capacitance from the followed solves' bonds, terms and W.
  void finish_woodbury(FollowedSolves& cache) const;
  // A column of U (left) or V from one flattened coupling term of a slipping contact.
  LinearBackend::Column coupling_column(std::int64_t bond, const std::vector<double>& terms,
                                        bool left) const;
  // UMFPACK's iterative refinement (up to 2 steps, each a residual and a solve), on only
  // for the fresh retry after an answer missed the tolerance: every answer is checked
  // against the residual anyway, and without it a solve is one pair of triangular
  // solves, not up to three and two residuals (docs/benchmarks.md, "The LU's refinement").
  bool lu_refinement_ = false;
  void unsymmetric_solve(const std::vector<std::int64_t>& slipping, double* rhs,
                         std::int64_t n, int columns);
  void factorize_unsymmetric(const std::vector<std::int64_t>& slipping, std::int64_t n);
  std::vector<std::uint8_t> lu_factored_states_;  // pair states at the LU's factorization
  std::vector<double> lu_factored_directions_;    // and the senses of slip (3 per bond)
  // Every stick contact off the boundary: its anchor loads the free dofs at zero free
  // displacement (update_loads).
  std::vector<std::int64_t> anchored_pairs() const;
  // Rank update of the factor with the columns sqrt(w) (e_j - e_i) (x) v on the free dofs.
  void update_factor(std::int64_t bond, const std::vector<RankOneTerm>& terms, bool downdate);
  long updates_since_factorization_ = 0;
  // The last checked solution and its lambda, and the forces that the factor updates since
  // then took out of it or added to it, on the free dofs. At the same lambda the new
  // solution is that one plus K^-1 (those forces): a right-hand side with a few entries per
  // update, which the updated factor solves at about half the cost of a full one
  // (LinearBackend::solve_sparse). The residual check still guards the result.
  void remember_solution(const Vector& free_displacement, double lambda);
  // Appends v on node j's free dofs and -v on node i's (the pattern of bond (i, j)).
  void append_on_bond(std::int64_t bond, const Vec3& v, LinearBackend::Column& column) const;
  void record_force_change(std::int64_t bond, const std::vector<RankOneTerm>& terms,
                           bool downdate);
  Vector last_solution_;
  double last_lambda_ = 0;
  bool last_solution_valid_ = false;
  LinearBackend::Column pending_forces_;
  std::vector<std::uint8_t> factored_states_;
  std::vector<std::pair<std::int64_t, std::uint8_t>> changes_since_factorization_;

  Model& model_;
  ModelEditor editor_;
  SolverOptions options_;
  StiffnessMatrix stiffness_;
  std::unique_ptr<LinearBackend> factor_;
  bool factor_current_ = false;
  SolverCounters counters_;
  std::unique_ptr<Kinsol> kinsol_;
};

}  // namespace latfrac
