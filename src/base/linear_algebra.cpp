// The NaN-safe largest magnitude.
#include "latfrac/base/linear_algebra.h"

#include <limits>

namespace latfrac {

double max_abs(const Vector& v) {
  if (!v.allFinite()) return std::numeric_limits<double>::infinity();
  return v.size() ? v.cwiseAbs().maxCoeff() : 0.0;
}

}  // namespace latfrac
