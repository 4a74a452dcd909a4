// The outer Mohr circle and the elliptic maximum over the planes through a point.
#include "mohr_circle.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <vector>

namespace latfrac {
namespace {

EllipticParts elliptic_on_circle(const MohrCircle& circle, double x, double sigma0, double tau0) {
  const double normal = std::max(circle.centre + circle.radius * x, 0.0) / sigma0;
  const double shear_squared = circle.radius * circle.radius * std::max(1 - x * x, 0.0);
  return {normal * normal, shear_squared / (tau0 * tau0)};
}

}  // namespace

MohrCircle outer_circle(const VoigtStress& s, int dim) {
  if (dim == 2) {
    return {0.5 * (s[0] + s[2]), std::hypot(0.5 * (s[0] - s[2]), s[4])};
  }
  const Eigen::Vector3d principal =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(stress_matrix(s)).eigenvalues();
  return {0.5 * (principal(2) + principal(0)), 0.5 * (principal(2) - principal(0))};
}

// g(x) = <c + r x>+^2 / sigma0^2 + r^2 (1 - x^2) / tau0^2 on [-1, 1] (x = cos phi) is a
// quadratic on each side of the kink x = -c / r, so its maximum lies at an end, at the
// kink, at x = 0 (the stationary point where the normal part is 0) or at the stationary
// point of the tensile piece, x = c tau0^2 / (r (sigma0^2 - tau0^2)).
EllipticParts elliptic_maximum(const MohrCircle& circle, double sigma0, double tau0) {
  const double c = circle.centre, r = circle.radius;
  std::vector<double> candidates = {-1.0, 0.0, 1.0};
  if (r > 0) {
    candidates.push_back(-c / r);
    const double a = sigma0 * sigma0, b = tau0 * tau0;
    if (a != b && std::isfinite(b)) candidates.push_back(c * b / (r * (a - b)));
  }
  EllipticParts best;
  for (double x : candidates) {
    if (!std::isfinite(x)) continue;
    const EllipticParts parts = elliptic_on_circle(circle, std::clamp(x, -1.0, 1.0), sigma0, tau0);
    if (parts.value() > best.value()) best = parts;
  }
  return best;
}

}  // namespace latfrac
