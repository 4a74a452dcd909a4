// Poisson-disk points in a box, with points on its corners, edges and faces.
//
// Bridson's algorithm (30 attempts per active point, a background grid of cell r/sqrt(D)
// holding at most one point): every pair of points is at least r apart, and no gap larger
// than about 2r is left. The box is filled in stages, each seeded with the points already
// on its flat and checked against every point placed so far: the 2^D corners, then the
// edges (1-D), then in 3-D the faces (2-D), then the interior. Boundary points have a
// coordinate exactly 0 or L, so the walls are flat.
//
// The wall guard: a point that is not on a face must not own a piece of it (its Voronoi
// cell must not touch it), or a roller or traction on that face would miss that piece.
// A point's cell touches the face exactly when the point lies inside an empty ball
// centred on the face; the largest such balls are the diametral balls of consecutive
// points on a box edge and the circumballs of the 2-D Delaunay triangles of a face's
// points whose centres lie in the face. Each stage after the edges rejects candidates
// inside the balls of the stages before it. So no interior point lies within r/sqrt(2) of
// a face (about 0.52 a), and the rule "within a/2 of a face: on the face" picks exactly
// the points placed on it.
//
// Reproducible bit for bit: the numbers come from SeededRandom, offsets in the annulus
// r <= |d| < 2r by rejection in a cube (no sin, cos or other libm calls, whose last bit
// may differ between libraries), and only + - * / and sqrt, which IEEE 754 rounds exactly.
#pragma once

#include <cstdint>
#include <vector>

#include "latfrac/base/linear_algebra.h"

namespace latfrac {

// The minimum distance r that gives a mean spacing a: the sampler fills the interior at
// the number density rho r^2 = 0.6148 (2-D) and rho r^3 = 0.5767 (3-D) (measured), and r
// is chosen so that rho is the regular lattice's, 2 / (sqrt(3) a^2) and sqrt(2) / a^3.
double poisson_disk_distance(int dim, double spacing);

// The points of the box [0, extent] (2-D: its x and z; y = 0), at least min_distance
// apart, drawn with `seed`.
std::vector<Vec3> poisson_disk_points(int dim, const Vec3& extent, double min_distance,
                                      std::uint64_t seed);

}  // namespace latfrac
