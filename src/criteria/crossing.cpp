// The shared parts of the closed-form crossings, and bisection for convex failure indices.
#include "latfrac/criteria/crossing.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "crossing_parts.h"

namespace latfrac {
namespace {

// A discriminant this close to 0, relative to b^2 + |4ac|, is a double root.
constexpr double discriminant_rounding = 8 * std::numeric_limits<double>::epsilon();

}  // namespace

namespace crossing_parts {

AffineBondStress moved_to(const AffineBondStress& s, double l) {
  return {s.normal0 + l * s.normal1, s.normal1, s.shear0 + l * s.shear1, s.shear1};
}

Quadratic tensile_part(const AffineBondStress& s, double sigma0) {
  return {0, s.normal1 / sigma0, s.normal0 / sigma0 - 1};
}

Quadratic shear_part(const AffineBondStress& s, double tau0) {
  const Eigen::Vector3d t0 = s.shear0 / tau0, t1 = s.shear1 / tau0;
  return {t1.squaredNorm(), 2 * t0.dot(t1), t0.squaredNorm() - 1};
}

double to_lambda(double from, double x, double to) {
  if (x == infinity) return infinity;
  if (x == 0) return from;
  const double l = std::min(from + x, to);
  return l > from ? l : std::nextafter(from, infinity);
}

}  // namespace crossing_parts

QuadraticRoots real_roots(double a, double b, double c) {
  if (a == 0) {
    if (b == 0) return {};
    return {1, {-c / b, 0}};
  }
  double discriminant = b * b - 4 * a * c;
  const double rounding = discriminant_rounding * (b * b + std::abs(4 * a * c));
  if (discriminant < -rounding) return {};
  if (discriminant <= rounding) discriminant = 0;
  const double q = -0.5 * (b + std::copysign(std::sqrt(discriminant), b));
  if (q == 0) return {2, {0, 0}};
  double first = q / a, second = c / q;
  if (first > second) std::swap(first, second);
  return {2, {first, second}};
}

double first_crossing_convex(const std::function<double(double)>& f, double from, double to) {
  if (f(from) >= 1) return from;
  if (!(to > from) || f(to) < 1) return crossing_parts::infinity;
  double below = from, above = to;
  for (int i = 0; i < 200; ++i) {
    const double middle = 0.5 * (below + above);
    if (middle <= below || middle >= above) break;  // adjacent doubles
    if (above - below <= 4 * std::numeric_limits<double>::epsilon() *
                             std::max(std::abs(below), std::abs(above)))
      break;
    (f(middle) >= 1 ? above : below) = middle;
  }
  return above;
}

}  // namespace latfrac
