// Grabens: pairs of faults dipping towards each other that bound a block (docs/fault-analysis.md).
#pragma once

#include <vector>

#include "latfrac/analysis/fault_analysis.h"

namespace latfrac {

// Inclined faults (not diffuse, not along a wall, dip between 20 and 80 deg) pair up when the
// left one descends towards +x, the right one towards -x, their traces meet below the surface
// and both faults lie above that point. A pair is a graben unless another such pair lies
// within its block: nested faults give the innermost graben. The subsidence compares the
// top-row nodes between the two traces with those outside, leaving out a band of one
// spacing on each side of either trace. Ordered by left_surface_x.
std::vector<Graben> find_grabens(const RunResult& result, const Snapshot& snapshot,
                                 const std::vector<Fault>& faults, const FaultOptions& options);

}  // namespace latfrac
