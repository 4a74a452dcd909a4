// An isotropic elastic material: what the springs are calibrated from.
#pragma once

namespace latfrac {

struct Material {
  double density = 0;  // kg/m^3
  double young = 0;    // Pa
  double poisson = 0;  // dimensionless, -1 < nu <= 1/4
};

}  // namespace latfrac
