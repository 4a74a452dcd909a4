// Recording the lattice and a state of the model into a RunResult.
#pragma once

#include "latfrac/criteria/failure_evaluator.h"
#include "latfrac/mechanics/model.h"
#include "latfrac/fracture/run_result.h"

namespace latfrac {

// Positions, bonds and bond kinds.
void record_lattice(const Model& model, RunResult& result);

// The state at lambda: displacement, intact flags, failure indices (0 without a
// criterion, i.e. when evaluator is null), node stresses.
Snapshot make_snapshot(const Model& model, const Vector& displacement, double lambda,
                       const FailureEvaluator* evaluator);

}  // namespace latfrac
