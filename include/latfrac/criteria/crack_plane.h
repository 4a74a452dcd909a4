// The plane a broken bond's crack lies in, for a contact that acts across the crack
// (contact.normal = "crack"; docs/model.md, section 8, "Which way a contact pushes").
//
// A bond stands for the rock between two nodes, a kilometre of it at crustal spacings.
// When it fails, the crack it stands for forms on the plane the stress picks, not
// perpendicular to the bond:
//   - in tension, perpendicular to the least compressive principal stress sigma3;
//   - in shear, on a Coulomb plane: its normal in the sigma1-sigma3 plane at
//     45 + phi/2 degrees from sigma1 (the plane at 45 - phi/2 from sigma1), of the two
//     conjugate planes the one whose normal is nearer the bond's direction (the bond's
//     own facet is the failure the criterion read).
// A pre-cut's bonds take the cut's normal. The normal is oriented from node i to node j
// (n . n0 > 0), as the bond's direction n0 is.
#pragma once

#include "latfrac/base/linear_algebra.h"
#include "latfrac/criteria/stress.h"

namespace latfrac {

// stress: the stress at the bond (Voigt, Pa, compression negative; in 2-D the x-z
// components are read: the in-plane principal stresses); bond_direction: the bond's unit n0 from i
// to j; mode: how it failed (tensile or shear); friction_angle: phi, radians, in [0, pi/2). dim 2
// or 3. Returns a unit vector with n . n0 > 0 (in 2-D, y = 0). A stress with no deviatoric part
// (every direction principal) gives n0.
Vec3 crack_plane_normal(const VoigtStress& stress, const Vec3& bond_direction, BreakMode mode,
                        double friction_angle, int dim);

}  // namespace latfrac
