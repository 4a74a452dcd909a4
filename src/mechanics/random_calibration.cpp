// Random lattices' spring parameters: (E, nu) -> (En, alpha) from the measured table.
#include "latfrac/mechanics/random_calibration.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "latfrac/base/error.h"

namespace latfrac {
namespace {

// Fritsch-Carlson end slope: the three-point estimate, limited so the curve stays monotone.
double end_slope(double h0, double h1, double d0, double d1) {
  double slope = ((2 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
  if (slope * d0 <= 0) return 0;
  if (d0 * d1 <= 0 && std::abs(slope) > std::abs(3 * d0)) return 3 * d0;
  return slope;
}

// The measured tables: table_2d and table_3d.
#include "random_calibration_table.inc"

}  // namespace

const RandomCalibrationTable& random_calibration_table(int dim) {
  return dim == 2 ? table_2d : table_3d;
}

double random_lattice_max_poisson(int dim) { return random_calibration_table(dim).poisson.front(); }

double monotone_cubic(const std::vector<double>& x, const std::vector<double>& y, double xq) {
  const int n = static_cast<int>(x.size());
  if (xq <= x.front()) return y.front();
  if (xq >= x.back()) return y.back();
  std::vector<double> h(n - 1), secant(n - 1), slope(n);
  for (int k = 0; k < n - 1; ++k) {
    h[k] = x[k + 1] - x[k];
    secant[k] = (y[k + 1] - y[k]) / h[k];
  }
  for (int k = 1; k < n - 1; ++k) {
    if (secant[k - 1] * secant[k] <= 0) {
      slope[k] = 0;
      continue;
    }
    const double w1 = 2 * h[k] + h[k - 1], w2 = h[k] + 2 * h[k - 1];
    slope[k] = (w1 + w2) / (w1 / secant[k - 1] + w2 / secant[k]);
  }
  slope[0] = n > 2 ? end_slope(h[0], h[1], secant[0], secant[1]) : secant[0];
  slope[n - 1] = n > 2 ? end_slope(h[n - 2], h[n - 3], secant[n - 2], secant[n - 3]) : secant[0];
  const int k = static_cast<int>(std::upper_bound(x.begin(), x.end(), xq) - x.begin()) - 1;
  const double t = (xq - x[k]) / h[k], t2 = t * t, t3 = t2 * t;
  return (2 * t3 - 3 * t2 + 1) * y[k] + (t3 - 2 * t2 + t) * h[k] * slope[k] +
         (-2 * t3 + 3 * t2) * y[k + 1] + (t3 - t2) * h[k] * slope[k + 1];
}

RandomSpringParameters random_spring_parameters(int dim, const Material& material,
                                                const char* where) {
  const double largest = random_lattice_max_poisson(dim);
  if (!(material.young > 0) || !std::isfinite(material.young)) {
    throw InputError(std::string(where) + ".young: must be a positive modulus in Pa");
  }
  if (!(material.poisson >= 0) || !(material.poisson <= largest)) {
    std::ostringstream message;
    message << where << ".poisson: " << material.poisson << " is outside 0 <= nu <= " << largest
            << ", the range of a random " << dim
            << "-D lattice (0 needs ks = kn, the largest ks = 0; docs/model.md)";
    throw InputError(message.str());
  }
  const RandomCalibrationTable& table = random_calibration_table(dim);
  // nu falls as alpha rises: interpolate alpha(nu) on the reversed table.
  const std::vector<double> poisson(table.poisson.rbegin(), table.poisson.rend());
  const std::vector<double> ratio(table.shear_ratio.rbegin(), table.shear_ratio.rend());
  RandomSpringParameters parameters;
  parameters.shear_ratio = std::clamp(monotone_cubic(poisson, ratio, material.poisson), 0.0, 1.0);
  parameters.normal_modulus =
      material.young / monotone_cubic(table.shear_ratio, table.young_ratio, parameters.shear_ratio);
  return parameters;
}

}  // namespace latfrac
