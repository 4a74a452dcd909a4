// The outer Mohr circle of a stress tensor, and the elliptic criterion's largest value on it.
//
// A plane whose normal makes the angle phi / 2 with the largest principal stress s1
// carries sigma_n = c + r cos phi and tau = r sin phi, with centre c = (s1 + s3) / 2 and
// radius r = (s1 - s3) / 2 (s3 the smallest principal stress; in 2-D of the x-z part of
// the tensor, the planes that contain the y axis). Every stress criterion here grows with
// <sigma_n>+ and tau, so its largest value over all planes lies on that circle.
#pragma once

#include "latfrac/criteria/stress.h"

namespace latfrac {

// Centre and radius of the outer Mohr circle (Pa).
struct MohrCircle {
  double centre = 0, radius = 0;
};
MohrCircle outer_circle(const VoigtStress& stress, int dim);

// The elliptic f on a plane of the circle, by its two parts.
struct EllipticParts {
  double normal = 0, shear = 0;  // (<sigma_n>+ / sigma0)^2 and (tau / tau0)^2
  double value() const { return normal + shear; }
};
// The largest (<sigma_n>+ / sigma0)^2 + (tau / tau0)^2 over the planes of the circle.
EllipticParts elliptic_maximum(const MohrCircle& circle, double sigma0, double tau0);

}  // namespace latfrac
