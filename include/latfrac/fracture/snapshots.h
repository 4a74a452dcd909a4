// Recording the lattice and states of the model into a RunResult, and when to take them.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include "latfrac/criteria/failure_evaluator.h"
#include "latfrac/fracture/run_result.h"
#include "latfrac/mechanics/model.h"

namespace latfrac {

// Positions, bonds and bond kinds.
void record_lattice(const Model& model, RunResult& result);

// The state at lambda: displacement, intact flags, failure indices (0 without a
// criterion, i.e. when evaluator is null), node stresses.
Snapshot make_snapshot(const Model& model, const Vector& displacement, double lambda,
                       const FailureEvaluator* evaluator);

// The lambdas at which a run takes snapshots (the end when none are asked for), in order,
// and which of them are still to come.
class SnapshotSchedule {
 public:
  SnapshotSchedule(const std::vector<double>& requested, double total);
  // Calls take(at) for every snapshot lambda up to `lambda` (|at| <= |lambda| + slack when
  // inclusive, |at| < |lambda| otherwise) that has not been taken, in order.
  template <typename Take>
  void take_until(double lambda, bool inclusive, Take take, double slack = 0) {
    while (next_ < lambdas_.size() &&
           (inclusive ? std::abs(lambdas_[next_]) <= std::abs(lambda) + slack
                      : std::abs(lambdas_[next_]) < std::abs(lambda))) {
      take(lambdas_[next_++]);
    }
  }
  // The next snapshot lambda, or `otherwise` when all are taken.
  double next_or(double otherwise) const { return next_ < lambdas_.size() ? lambdas_[next_] : otherwise; }
  // How many are taken; a resumed run's count.
  std::size_t taken() const { return next_; }
  void restore(std::size_t taken) { next_ = taken; }

 private:
  std::vector<double> lambdas_;
  std::size_t next_ = 0;
};

}  // namespace latfrac
