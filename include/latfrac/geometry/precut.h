// Pre-cut faults: which bonds of a lattice a [[precut]] severs before loading starts.
//
// A bond is cut when its reference segment [X_i, X_j] crosses a pre-cut:
//   2-D: the cut is the segment from -> to in the x-z plane;
//   3-D: the cut is the parallelogram corner + s edge1 + t edge2, s, t in [0, 1].
// The rule, with eps = 1e-9 a (a the lattice spacing), is:
//   1. the bond's two ends lie strictly on opposite sides of the cut's line (2-D) or
//      plane (3-D): one signed distance > +eps, the other < -eps;
//   2. the point where the bond meets that line or plane lies within the cut, ends and
//      edges included, give or take eps.
// So a bond that only touches the cut (a node on the cut, a bond lying in it) is not cut,
// whereas a bond that meets the cut exactly at its end is. Consequences: a cut that
// passes through a row of nodes cuts nothing on that row (place cuts between nodes, e.g.
// at a/4 from a node); two cuts that meet end to end sever the same bonds as the joined
// cut. A cut of zero length or area, or one outside the body, cuts nothing.
// docs/precuts.md explains the rule with a sketch.
#pragma once

#include <cstdint>
#include <vector>

#include "latfrac/geometry/lattice.h"

namespace latfrac {

// A pre-cut fault: bonds whose segment crosses it start broken.
// 2-D: the segment from -> to in the x-z plane (y components are 0).
// 3-D: the rectangle corner + s edge1 + t edge2, s, t in [0, 1].
struct Precut {
  std::array<double, 3> from{0, 0, 0}, to{0, 0, 0};                       // 2-D, m
  std::array<double, 3> corner{0, 0, 0}, edge1{0, 0, 0}, edge2{0, 0, 0};  // 3-D, m
};

// The unit normal of a pre-cut's line (2-D, in the x-z plane) or plane (3-D): the one the
// crossing rule uses. Zero for a degenerate cut (zero length or area), which cuts nothing.
Vec3 precut_normal(const Precut& precut, int dim);

// Ids of the bonds whose segment [X_i, X_j] crosses any pre-cut (sorted, unique).
// The lattice's dim chooses the reading of each Precut (from/to or corner/edges).
std::vector<std::int64_t> bonds_crossing_precuts(const Lattice& lattice,
                                                 const std::vector<Precut>& precuts);

}  // namespace latfrac
