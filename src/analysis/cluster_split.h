// Splits a cluster of broken bonds that one line or plane does not fit into straight faults.
//
// Faults that touch form one cluster: two graben faults meeting at depth (a V), two faults
// leaving one point downwards (an inverted V), a branch (a Y), a zigzag, a crossing (an X).
// The cluster is divided between several lines (planes in 3-D) by k-lines (k-planes) from
// deterministic seeds along its principal axes, recursively, and a division stands only if
// its parts fit much better than the whole and every final part is a fault by the fitter's
// rules. A shattered region's pieces are no faults either, so it stays whole.
// docs/fault-analysis.md, "Splitting branched clusters", gives the rule and its constants.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "fault_fit.h"
#include "latfrac/analysis/fault_analysis.h"

namespace latfrac {

// The faults of `cluster`, a connected cluster given as increasing indices into `midpoints`
// (m): its straight parts, each a list of indices into `midpoints`, if it resolves into parts
// that `fitter` finds are all faults; else the whole cluster as its one part. The parts hold
// every index of the cluster once. Uses the link, min_bonds and split options; spacing in m.
std::vector<std::vector<std::size_t>> split_cluster(const std::vector<Eigen::Vector3d>& midpoints,
                                                    const std::vector<std::size_t>& cluster,
                                                    const FaultFitter& fitter,
                                                    const FaultOptions& options, double spacing);

}  // namespace latfrac
