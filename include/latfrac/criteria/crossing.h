// Crossings: the exact lambda at which a bond's failure index reaches 1 on an affine path.
//
// With small kinematics and a fixed set of intact bonds the equilibrium path is affine in
// lambda, and so is every bond quantity: sigma_n(l) = sn0 + l sn1, the shear stress vector
// t(l) = t0 + l t1 (tau = |t|), the stress tensor S(l) = S0 + l S1. Each criterion then
// reaches f = 1 at a root of a polynomial of degree <= 2 (docs/criteria.md):
//   tensile           sn(l) = sigma0                                   linear
//   shear part        |t(l)|^2 = tau0^2                                quadratic
//   tensile_or_shear  the earlier of the two
//   elliptic          split where sn changes sign; where sn <= 0 only the shear part
//                     counts, where sn > 0 (sn/sigma0)^2 + |t|^2/tau0^2 = 1   quadratic
//   drucker_prager    sqrt(J2(l)) = k - alpha I1(l): squared, J2(l) - (k - alpha I1(l))^2 = 0,
//                     keeping only roots with k - alpha I1(l) >= 0
// Every f is convex along an affine path (a norm plus a linear term, or a sum of squares
// of such), so once f(from) < 1 there is at most one crossing after 'from' and f rises
// through it. Each criterion's own crossing is in its file; this header has what they share.
#pragma once

#include <Eigen/Core>
#include <array>
#include <functional>

namespace latfrac {

struct AffineBondStress {
  double normal0 = 0, normal1 = 0;  // sigma_n = normal0 + l normal1, Pa
  Eigen::Vector3d shear0 = Eigen::Vector3d::Zero(), shear1 = Eigen::Vector3d::Zero();  // Pa
};

// The smallest l in (from, to] with f(l) >= 1 for any f that is continuous and convex
// along the path (the critical-plane reading: a maximum over planes of convex functions of
// l): once f(from) < 1, f reaches 1 in (from, to] only if f(to) >= 1, and then once.
// Bisection brackets that point to within a few ulps of l and returns the upper end, where
// f >= 1. `from` when f(from) >= 1, +infinity when f(to) < 1.
double first_crossing_convex(const std::function<double(double)>& f, double from, double to);

// The real roots of a x^2 + b x + c = 0, ascending, without cancellation (the root of
// larger magnitude from q = -(b + sign(b) sqrt(b^2 - 4ac)) / 2, the other as c / q).
// a = 0 gives the linear root; a discriminant within rounding of 0 counts as a double root.
struct QuadraticRoots {
  int count = 0;
  std::array<double, 2> root{0, 0};
};
QuadraticRoots real_roots(double a, double b, double c);

}  // namespace latfrac
