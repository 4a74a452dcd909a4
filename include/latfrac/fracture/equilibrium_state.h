// The equilibrium a fracture run is at: how it is computed, what is cached, and how the
// model is changed.
//
// Three methods, chosen once from the scene: with a linear law, the closed-form affine
// path u(lambda) = u_g + lambda u_e of the current stiffness (one factorization, then
// factor updates); with a nonlinear law, KINSOL's Newton iteration from the last state;
// with solver.method = "relaxation", Gauss-Seidel from the last state. Either way the
// caller asks for the displacement at a lambda and gets the equilibrium of the model as it
// is now.
//
// One validity rule: the cached state (at its lambda) and the cached path describe the
// model as it is. Every change goes through change_pairs(), which changes the pairs (the
// solver updates its factor), holds what they cut loose and re-equilibrates before it
// returns, so no stale state can be read. The safety net for singular stiffness (a
// factorization that finds no stiffness along some motion holds that one unknown and tries
// again) invalidates both.
#pragma once

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "latfrac/fracture/run_control.h"
#include "latfrac/fracture/run_result.h"
#include "latfrac/mechanics/fragments.h"
#include "latfrac/solvers/equilibrium.h"
#include "latfrac/solvers/relaxation.h"

namespace latfrac {

// One pair's new state (into slip: the sense of sliding; zero: that of its force).
struct PairChange {
  std::int64_t bond;
  PairState state;
  Vec3 direction = Vec3::Zero();
};

class EquilibriumState {
 public:
  EquilibriumState(Model& model, EquilibriumSolver& solver, const SolverOptions& options);

  const Model& model() const { return model_; }
  EquilibriumSolver& solver() { return solver_; }
  // True when equilibria lie on closed-form affine paths (a linear law, a direct solver).
  bool affine() const { return model_.is_linear() && !relaxation_; }

  // The full displacement at lambda: the state last computed when it is at lambda,
  // otherwise the affine path at lambda, or a new equilibrium (Newton, relaxation).
  Vector displacement(double lambda);
  // The same on the free dofs.
  Vector free_state(double lambda);
  // The affine path of the current stiffness (solved, residual checked, when stale).
  const AffinePath& path(double lambda);
  // Whether path() has the current path at hand (no solve), and which one it is: the
  // count of paths solved so far.
  bool path_at_hand() const { return path_valid_; }
  std::uint64_t path_version() const { return path_version_; }

  // Puts each pair into its new state (in order; the solver updates its factor), holds
  // every part that a pair which stopped connecting its nodes cut loose, at `before` (the
  // full displacement before the change; docs/robustness.md), and re-equilibrates at
  // lambda.
  //
  // With friction, every contact's memory is first carried along to `before` (its slip
  // and work since the last commit), the changed pairs enter their new states there
  // (FrictionalContactLaw::entered), and after the new equilibrium the memories are
  // carried along again: each commit closes a stretch of affine path, or the jump at
  // lambda that a change makes (whose work the trapezoidal rule in dn approximates).
  void change_pairs(const std::vector<PairChange>& changes, double lambda, const Vector& before);
  // Before bond b breaks (contacts along cracks): the normal its contact will act along.
  void set_contact_normal(std::int64_t bond, const Vec3& normal) {
    solver_.set_contact_normal(bond, normal);
  }
  // Event-driven runs read the affine path after every change: then each change solves for
  // the path at once and takes the state on it (one solve with two load columns instead
  // of one for the state and one for the path).
  void want_paths(bool wanted) { paths_wanted_ = wanted; }
  // Carries every frictional contact's memory along to the equilibrium at lambda (the run
  // calls it at its end).
  void commit_contacts(double lambda);
  // Takes a free displacement computed elsewhere (the integrated path) as the state at lambda.
  void adopt(const Vector& free_state, double lambda);

  // The state the next solve starts from (run_control.h), and a resumed run's: the
  // parts held so far, that state, and the relaxation counts.
  void save(RunCheckpoint& checkpoint) const;
  void restore(const RunCheckpoint& checkpoint, const std::vector<FragmentEvent>& held,
               const RunCounters& counts);

  // Parts held for lack of support since the run started, in order.
  const std::vector<FragmentEvent>& fragments() const { return fragments_; }
  // With solver.method = "relaxation": relaxation solves, their sweeps, and those that
  // stopped at the sweep cap before reaching the tolerance.
  std::int64_t relaxation_solves() const { return relaxation_solves_; }
  std::int64_t relaxation_sweeps() const { return relaxation_sweeps_; }
  std::int64_t relaxation_unconverged() const { return relaxation_unconverged_; }

 private:
  // Re-equilibrates at lambda after the model changed.
  void resolve(double lambda);
  void commit_at(const Vector& displacement);
  // Runs `solve`; where a factorization finds no stiffness, holds that unknown and retries.
  template <typename Solve>
  auto holding_singular(double lambda, Solve solve);
  // Holds each loose part along the axes it lacks, at `before` (docs/robustness.md).
  void hold(const std::vector<FragmentDetector::LoosePart>& parts, double lambda,
            const Vector& before);
  // Newton (KINSOL) to equilibrium at lambda from the current state: the nonlinear law.
  void newton(double lambda);
  // Relaxes the state to equilibrium at lambda, starting from the current state.
  void relax(double lambda);
  void invalidate() { state_valid_ = path_valid_ = false; }

  Model& model_;
  EquilibriumSolver& solver_;
  FragmentDetector fragments_detector_;
  std::optional<RelaxationSolver> relaxation_;  // set when the scene asks for relaxation
  AffinePath path_;
  bool path_valid_ = false;  // path_ describes the current model
  std::uint64_t path_version_ = 0;
  bool paths_wanted_ = false;
  Vector state_;             // free displacement at state_lambda_ (also the next warm start)
  double state_lambda_ = 0;
  bool state_valid_ = false;
  std::vector<FragmentEvent> fragments_;
  std::int64_t relaxation_solves_ = 0, relaxation_sweeps_ = 0, relaxation_unconverged_ = 0;
};

}  // namespace latfrac
