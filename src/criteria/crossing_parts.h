// The parts the criteria's closed-form crossings are built from.
//
// Each search first moves the origin to 'from' (x = l - from), so that the constant term
// of every polynomial is g(0) = its value at 'from', negative when f(from) < 1. The sign of
// each root is then exact (it follows from the signs of a, b, c), and a crossing just
// after 'from' is never lost to rounding.
#pragma once

#include <limits>

#include "latfrac/criteria/crossing.h"

namespace latfrac::crossing_parts {

inline constexpr double infinity = std::numeric_limits<double>::infinity();

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

inline double first_nonnegative(const Quadratic& g, double length) {
  return first_nonnegative(g, length, [](double) { return true; });
}

// The stress moved to l: its value there becomes the constant term.
AffineBondStress moved_to(const AffineBondStress& s, double l);
// sn / sigma0 - 1.
Quadratic tensile_part(const AffineBondStress& s, double sigma0);
// |t|^2 / tau0^2 - 1 (identically -1 when tau0 = +inf).
Quadratic shear_part(const AffineBondStress& s, double tau0);
// |t|^2 / tau0^2 - (1 - mu sn / tau0)^2: the shear part with the strength tau0 - mu sn,
// valid where sn <= 0 (there the strength is positive, so the sign is that of
// |t| - (tau0 - mu sn)).
Quadratic pressure_shear_part(const AffineBondStress& s, double tau0, double mu);
// The pieces of [0, length] on which sn keeps its sign (split where it changes sign): one
// or two, each with its stress moved to its start (sn exactly 0 at a split) and whether
// sn > 0 on it (by its middle).
struct SignPiece {
  double from, to;
  AffineBondStress stress;
  bool tension;
};
int sign_pieces(const AffineBondStress& start, double length, SignPiece (&pieces)[2]);
// The first x in [0, length] where the shear part reaches 1 with the strength
// tau0 + mu <-sn>+ (mu = 0: tau0 throughout); +infinity when none.
double first_shear_crossing(const AffineBondStress& start, double tau0, double mu, double length);
// From the local offset x back to lambda, strictly after 'from' unless x = 0.
double to_lambda(double from, double x, double to);

}  // namespace latfrac::crossing_parts
