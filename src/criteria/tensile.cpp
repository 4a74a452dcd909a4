// The tensile criterion: f = <sigma_n>+ / sigma0 (on the critical plane: Rankine).
#include <algorithm>

#include "criterion_makers.h"
#include "crossing_parts.h"
#include "mohr_circle.h"

namespace latfrac {
namespace {

using namespace crossing_parts;

class Tensile final : public FailureCriterion {
 public:
  using FailureCriterion::FailureCriterion;

  FailureIndex index(double sigma_n, double, const BondStrength& strength) const override {
    return {std::max(sigma_n, 0.0) / strength.sigma0, BreakMode::tensile};
  }

  // The largest normal stress over all planes: the largest principal stress.
  FailureIndex tensor_index(const VoigtStress& stress, const BondStrength& strength) const override {
    const MohrCircle circle = outer_circle(stress, dim());
    return {std::max(circle.centre + circle.radius, 0.0) / strength.sigma0, BreakMode::tensile};
  }

  double first_crossing(const AffineBondStress& stress, const BondStrength& strength, double from,
                        double to) const override {
    const AffineBondStress start = moved_to(stress, from);
    if (index(start.normal0, start.shear0.norm(), strength).value >= 1) return from;
    return to_lambda(from, first_nonnegative(tensile_part(start, strength.sigma0), to - from), to);
  }

  double rank(double normal_ratio, double) const override { return normal_ratio; }
};

}  // namespace

std::unique_ptr<FailureCriterion> make_tensile(const CriterionParameters& parameters) {
  return std::make_unique<Tensile>(parameters);
}

}  // namespace latfrac
