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

Quadratic pressure_shear_part(const AffineBondStress& s, double tau0, double mu) {
  const Eigen::Vector3d t0 = s.shear0 / tau0, t1 = s.shear1 / tau0;
  const double h0 = 1 - mu * s.normal0 / tau0, h1 = -mu * s.normal1 / tau0;
  return {t1.squaredNorm() - h1 * h1, 2 * (t0.dot(t1) - h0 * h1), t0.squaredNorm() - h0 * h0};
}

int sign_pieces(const AffineBondStress& start, double length, SignPiece (&pieces)[2]) {
  double bounds[3] = {0, length, length};
  int count = 1;
  if (start.normal1 != 0) {
    const double zero = -start.normal0 / start.normal1;
    if (zero > 0 && zero < length) {
      bounds[1] = zero;
      count = 2;
    }
  }
  for (int p = 0; p < count; ++p) {
    const double lo = bounds[p], hi = bounds[p + 1];
    AffineBondStress piece = moved_to(start, lo);
    if (p > 0) piece.normal0 = 0;
    pieces[p] = {lo, hi, piece, piece.normal0 + 0.5 * (hi - lo) * piece.normal1 > 0};
  }
  return count;
}

double first_shear_crossing(const AffineBondStress& start, double tau0, double mu, double length) {
  if (mu == 0) return first_nonnegative(shear_part(start, tau0), length);
  SignPiece pieces[2];
  const int count = sign_pieces(start, length, pieces);
  for (int p = 0; p < count; ++p) {
    const SignPiece& piece = pieces[p];
    const Quadratic g = piece.tension ? shear_part(piece.stress, tau0)
                                      : pressure_shear_part(piece.stress, tau0, mu);
    const double x = first_nonnegative(g, piece.to - piece.from);
    if (x < infinity) return piece.from + x;
  }
  return infinity;
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
