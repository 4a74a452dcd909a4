// Closed-form crossings of f = 1 along affine paths, for event-driven breaking.
//
// Each search first moves the origin to 'from' (x = l - from), so that the constant term
// of every polynomial is g(0) = its value at 'from', negative when f(from) < 1. The sign of
// each root is then exact (it follows from the signs of a, b, c), and a crossing just
// after 'from' is never lost to rounding.
#include "latfrac/criteria/crossing.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "latfrac/criteria/criterion.h"
#include "latfrac/base/error.h"

namespace latfrac {
namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();
// A discriminant this close to 0, relative to b^2 + |4ac|, is a double root.
constexpr double discriminant_rounding = 8 * std::numeric_limits<double>::epsilon();
// Near r = 0 both square-root branches meet; a root with r this small (relative to its
// terms) is on the admissible branch within rounding.
constexpr double branch_tolerance = 1e-9;

// g(x) = a x^2 + b x + c in the local coordinate x >= 0 of one search interval.
struct Quadratic {
  double a = 0, b = 0, c = 0;
};

// Smallest x in [0, length] with g(x) >= 0 and admissible(x); +infinity when none.
template <class Admissible>
double first_nonnegative(const Quadratic& g, double length, Admissible admissible) {
  if (g.c >= 0 && admissible(0.0)) return 0;
  const QuadraticRoots roots = real_roots(g.a, g.b, g.c);
  for (int i = 0; i < roots.count; ++i) {
    const double x = roots.root[i];
    if (x > 0 && x <= length && admissible(x)) return x;
  }
  return infinity;
}

double first_nonnegative(const Quadratic& g, double length) {
  return first_nonnegative(g, length, [](double) { return true; });
}

AffineBondStress moved_to(const AffineBondStress& s, double l) {
  return {s.normal0 + l * s.normal1, s.normal1, s.shear0 + l * s.shear1, s.shear1};
}

// sn / sigma0 - 1.
Quadratic tensile_part(const AffineBondStress& s, double sigma0) {
  return {0, s.normal1 / sigma0, s.normal0 / sigma0 - 1};
}

// |t|^2 / tau0^2 - 1 (identically -1 when tau0 = +inf).
Quadratic shear_part(const AffineBondStress& s, double tau0) {
  const Eigen::Vector3d t0 = s.shear0 / tau0, t1 = s.shear1 / tau0;
  return {t1.squaredNorm(), 2 * t0.dot(t1), t0.squaredNorm() - 1};
}

// (sn / sigma0)^2 + |t|^2 / tau0^2 - 1, valid where sn >= 0.
Quadratic ellipse(const AffineBondStress& s, double sigma0, double tau0) {
  Quadratic g = shear_part(s, tau0);
  const double n0 = s.normal0 / sigma0, n1 = s.normal1 / sigma0;
  g.a += n1 * n1;
  g.b += 2 * n0 * n1;
  g.c += n0 * n0;
  return g;
}

// The interval is split where sn changes sign: <sn>+ is 0 on one side.
double elliptic_crossing(const AffineBondStress& start, double sigma0, double tau0, double length) {
  std::array<double, 3> bounds{0, length, length};
  int pieces = 1;
  if (start.normal1 != 0) {
    const double zero = -start.normal0 / start.normal1;
    if (zero > 0 && zero < length) {
      bounds[1] = zero;
      pieces = 2;
    }
  }
  for (int p = 0; p < pieces; ++p) {
    const double lo = bounds[p], hi = bounds[p + 1];
    AffineBondStress piece = moved_to(start, lo);
    if (p > 0) piece.normal0 = 0;
    const bool tension = piece.normal0 + 0.5 * (hi - lo) * piece.normal1 > 0;
    const Quadratic g = tension ? ellipse(piece, sigma0, tau0) : shear_part(piece, tau0);
    const double x = first_nonnegative(g, hi - lo);
    if (x < infinity) return lo + x;
  }
  return infinity;
}

// From the local offset x back to lambda, strictly after 'from' unless x = 0.
double to_lambda(double from, double x, double to) {
  if (x == infinity) return infinity;
  if (x == 0) return from;
  const double l = std::min(from + x, to);
  return l > from ? l : std::nextafter(from, infinity);
}

// Squaring makes two roots of J2 - r^2 nearly coincide on near-hydrostatic paths, which
// costs up to half the digits (about 1e-8 relative). Newton steps on the unsquared
// phi(x) = sqrt(J2(x)) - r(x), whose slope at the crossing is positive (f is convex and
// rises through 1), restore full precision; a step is kept only when it reduces |phi|.
double polished(const VoigtStress& start, const VoigtStress& slope, double r0, double r1, double x,
                double length) {
  const auto phi = [&](double at, double* derivative) {
    VoigtStress s;
    for (int i = 0; i < 6; ++i) s[i] = start[i] + at * slope[i];
    const double deviatoric = std::sqrt(second_deviatoric_invariant(s));
    if (derivative) *derivative = j2_product(s, slope) / deviatoric - r1;
    return deviatoric - (r0 + r1 * at);
  };
  for (int step = 0; step < 2; ++step) {
    double derivative = 0;
    const double residual = phi(x, &derivative);
    if (residual == 0 || !(derivative > 0)) break;
    const double next = x - residual / derivative;
    if (!(next > 0 && next <= length) || std::abs(phi(next, nullptr)) >= std::abs(residual)) break;
    x = next;
  }
  return x;
}

}  // namespace

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

double first_crossing(Criterion criterion, const AffineBondStress& stress, double sigma0,
                      double tau0, double from, double to) {
  if (criterion == Criterion::drucker_prager) {
    throw Error(
        "first_crossing: drucker_prager needs the stress tensor "
        "(first_crossing_drucker_prager)");
  }
  const AffineBondStress start = moved_to(stress, from);
  if (failure_index(criterion, start.normal0, start.shear0.norm(), sigma0, tau0).value >= 1) {
    return from;
  }
  const double length = to - from;
  double x = infinity;
  switch (criterion) {
    case Criterion::tensile:
      x = first_nonnegative(tensile_part(start, sigma0), length);
      break;
    case Criterion::tensile_or_shear:
      x = std::min(first_nonnegative(tensile_part(start, sigma0), length),
                   first_nonnegative(shear_part(start, tau0), length));
      break;
    case Criterion::elliptic:
      x = elliptic_crossing(start, sigma0, tau0, length);
      break;
    case Criterion::drucker_prager:
      break;
  }
  return to_lambda(from, x, to);
}

double first_crossing_convex(const std::function<double(double)>& f, double from, double to) {
  if (f(from) >= 1) return from;
  if (!(to > from) || f(to) < 1) return infinity;
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

// sqrt(J2(x)) = r(x) with r = k - alpha I1, squared: J2(x) - r(x)^2 = 0. The square admits
// roots of sqrt(J2) = -r as well; those lie where alpha I1 > k, i.e. f > 1, and are dropped.
double first_crossing_drucker_prager(const std::array<double, 6>& s0,
                                     const std::array<double, 6>& s1, double alpha, double k,
                                     double from, double to) {
  VoigtStress start;
  for (int i = 0; i < 6; ++i) start[i] = s0[i] + from * s1[i];
  if (drucker_prager_index(start, alpha, k).value >= 1) return from;
  const double r0 = k - alpha * first_invariant(start);
  const double r1 = -alpha * first_invariant(s1);
  const Quadratic g{second_deviatoric_invariant(s1) - r1 * r1,
                    2 * (j2_product(start, s1) - r0 * r1),
                    second_deviatoric_invariant(start) - r0 * r0};
  const auto admissible = [&](double x) {
    return r0 + r1 * x >= -branch_tolerance * (std::abs(r0) + std::abs(r1 * x));
  };
  const double length = to - from;
  double x = first_nonnegative(g, length, admissible);
  if (x > 0 && x < infinity) x = polished(start, s1, r0, r1, x, length);
  return to_lambda(from, x, to);
}

}  // namespace latfrac
