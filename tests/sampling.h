// Brute-force references for the closed forms: the first crossing of f = 1 by sampling,
// and planes sampled densely in the x-z plane (2-D) or over the unit sphere (3-D).
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <numbers>

namespace latfrac::testing {

// The first l in [from, to] with f(l) >= 1: `samples` samples, then bisection to rounding
// on the first bracket; +infinity when no sample reaches 1 (a crossing narrower than a
// sample's width is missed, which the callers' random paths make rare).
template <class F>
double sampled_crossing(F f, double from, double to, int samples = 2000) {
  if (f(from) >= 1) return from;
  double lo = from;
  for (int i = 1; i <= samples; ++i) {
    double hi = i == samples ? to : from + (to - from) * i / samples;
    if (f(hi) < 1) {
      lo = hi;
      continue;
    }
    for (;;) {
      const double mid = 0.5 * (lo + hi);
      if (mid <= lo || mid >= hi) return hi;
      (f(mid) >= 1 ? hi : lo) = mid;
    }
  }
  return std::numeric_limits<double>::infinity();
}

// Calls visit(n) for unit normals n: 720 angles in the x-z plane (2-D), or 720 x 720 over
// the sphere (3-D).
template <class Visit>
void for_each_sampled_plane(int dim, Visit visit) {
  const int steps = 720;
  for (int i = 0; i < steps; ++i) {
    const double theta = std::numbers::pi * i / steps;
    for (int j = 0; j < (dim == 2 ? 1 : steps); ++j) {
      const double phi = 2 * std::numbers::pi * j / steps;
      visit(dim == 2 ? Eigen::Vector3d(std::cos(theta), 0, std::sin(theta))
                     : Eigen::Vector3d(std::sin(theta) * std::cos(phi),
                                       std::sin(theta) * std::sin(phi), std::cos(theta)));
    }
  }
}

}  // namespace latfrac::testing
