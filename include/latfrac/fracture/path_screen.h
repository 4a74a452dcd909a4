// Ruling bonds out of a crossing search by bounds, so that a path that differs little
// from one searched in full is searched only where a bond may cross.
//
// After a contact switch the equilibrium moves on a new affine path that leaves the
// state where it was and bends its direction, often for a tiny interval of lambda before
// the next switch (docs/benchmarks.md, "Where the events come from"). Every bond's
// crossing search would need the new path's node stresses: a sweep over every bond. The
// screen keeps a reference instead: the full displacement along the last path whose
// stresses were swept, and each intact bond's normal and shear stress along it. Node
// stresses are linear in the displacement, so on a new path u(s), with the same intact
// bonds and supports, a bond's normal and shear stress lie within
//     B_b max|u(s) - u_ref(s)|
// of the reference's (B_b the mean of its nodes' node_stress_bounds). Over the interval
// to be searched [from, until] that distance is at most
//     max|u(from) - u_ref(from)| + (until - from) max|u' - u_ref'|,
// and a bond whose f cannot reach 1 within it there (FailureEvaluator::may_cross_near,
// with the search's own 1e-9 margin) cannot cross. The others are searched exactly, on
// node stresses summed at their own nodes (node_stress_path_at, the sweep's numbers bit
// for bit), so the event found is the full search's: the same lambda, the same tied
// bonds. When too many bonds remain, or the bonds or supports have changed since the
// reference, the search is the full one and its stresses become the reference.
//
// Used on the stress tensor resolved on the bond, with a criterion whose index grows
// with stress, under the small-kinematics law, on one rank; elsewhere the full search.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "latfrac/criteria/failure_evaluator.h"
#include "latfrac/fracture/event_source.h"

namespace latfrac {

struct PathCrossing;

class PathScreen {
 public:
  // Whether the screen applies to this model and evaluator (see above).
  static bool applies(const Model& model, const FailureEvaluator& evaluator);
  PathScreen(const Model& model, const FailureEvaluator& evaluator);

  // The first crossing on `full` in (from, to] up to needed_until (next_break's meaning),
  // found from the reference with an exact search at the bonds it cannot rule out; none
  // (nullopt) when the screen cannot tell, and the caller searches in full. `breaks` is
  // the run's count of breaks: the reference is stale once it has changed.
  std::optional<PathCrossing> next_break(const FullPath& full, double from, double to,
                                         double needed_until, std::int64_t breaks);
  // Makes the path whose stresses were swept (in search direction sign) the reference.
  void set_reference(const FullPath& full, const PathStresses& stresses, double sign,
                     std::int64_t breaks);

  // Counts: searches answered by the screen, and searches made in full (set_reference).
  std::int64_t screened_searches() const { return screened_; }
  std::int64_t full_searches() const { return full_; }

  // More bonds left than this share of the intact ones: the full search instead. Chosen,
  // not measured: each bond left costs a node-stress sum at its two ends, about what the
  // full sweep spends on it.
  static constexpr double most_left = 0.125;

 private:
  const Model& model_;
  const FailureEvaluator& evaluator_;
  std::vector<double> bond_bound_;  // B_b, Pa per m
  bool valid_ = false;
  double sign_ = 0;
  std::int64_t breaks_ = 0;
  std::vector<std::int64_t> free_index_;  // the dof map of the reference
  Vector at_zero_, per_lambda_;           // the reference's full displacement
  std::vector<AffineBondStress> stress_;  // per bond, along the reference (in s)
  std::int64_t screened_ = 0, full_ = 0;
};

}  // namespace latfrac
