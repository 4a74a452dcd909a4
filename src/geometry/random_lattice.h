// The random lattice: Poisson-disk points, Delaunay bonds, Voronoi facets and cells.
//
// The points (poisson_disk.h) are at least r apart, r = 0.730 a (2-D) or 0.742 a (3-D)
// for the mean spacing a, so that there are as many nodes per volume as in the regular
// lattice of spacing a; the box's corners, edges and faces carry points of their own.
// Bonds are the Delaunay edges whose Voronoi facet has an area in the box
// (voronoi_network.h): about 6 per node in 2-D and 15 in 3-D (interior), of lengths 0.73 to 1.9 a.
// docs/model.md describes the construction and what it measured.
#pragma once

#include "latfrac/geometry/lattice.h"

namespace latfrac {

// The random lattice of `spec` (kind random): its extent, positions, bonds (kind delaunay)
// and Voronoi measures. build_lattice adds the faces and the bond directions and lengths.
Lattice build_random_lattice(const LatticeSpec& spec);

}  // namespace latfrac
