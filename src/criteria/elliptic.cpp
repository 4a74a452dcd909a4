// The elliptic (strain-energy) criterion, the paper's Eq. 3:
// f = (<sigma_n>+ / sigma0)^2 + (tau / (tau0 + mu_i <-sigma_n>+))^2.
#include <algorithm>

#include "criterion_makers.h"
#include "crossing_parts.h"
#include "mohr_circle.h"

namespace latfrac {
namespace {

using namespace crossing_parts;

// (sn / sigma0)^2 + |t|^2 / tau0^2 - 1, valid where sn >= 0.
Quadratic ellipse(const AffineBondStress& s, double sigma0, double tau0) {
  Quadratic g = shear_part(s, tau0);
  const double n0 = s.normal0 / sigma0, n1 = s.normal1 / sigma0;
  g.a += n1 * n1;
  g.b += 2 * n0 * n1;
  g.c += n0 * n0;
  return g;
}

// The interval is split where sn changes sign: <sn>+ is 0 on one side, and the shear
// strength tau0 + mu <-sn>+ is tau0 on the other.
double elliptic_crossing(const AffineBondStress& start, double sigma0, double tau0, double mu,
                         double length) {
  SignPiece pieces[2];
  const int count = sign_pieces(start, length, pieces);
  for (int p = 0; p < count; ++p) {
    const SignPiece& piece = pieces[p];
    const Quadratic g = piece.tension ? ellipse(piece.stress, sigma0, tau0)
                        : mu == 0     ? shear_part(piece.stress, tau0)
                                      : pressure_shear_part(piece.stress, tau0, mu);
    const double x = first_nonnegative(g, piece.to - piece.from);
    if (x < infinity) return piece.from + x;
  }
  return infinity;
}

class Elliptic final : public FailureCriterion {
 public:
  using FailureCriterion::FailureCriterion;

  FailureIndex index(double sigma_n, double tau, const BondStrength& strength) const override {
    const double normal = std::max(sigma_n, 0.0) / strength.sigma0;
    const double shear = tau / (strength.tau0 + mu() * std::max(-sigma_n, 0.0));
    return {normal * normal + shear * shear,
            normal >= shear ? BreakMode::tensile : BreakMode::shear};
  }

  // The maximum over the planes of the outer Mohr circle (mohr_circle.h).
  FailureIndex tensor_index(const VoigtStress& stress, const BondStrength& strength) const override {
    const EllipticParts parts =
        elliptic_maximum(outer_circle(stress, dim()), strength.sigma0, strength.tau0);
    return {parts.value(), parts.normal >= parts.shear ? BreakMode::tensile : BreakMode::shear};
  }

  double first_crossing(const AffineBondStress& stress, const BondStrength& strength, double from,
                        double to) const override {
    const AffineBondStress start = moved_to(stress, from);
    if (index(start.normal0, start.shear0.norm(), strength).value >= 1) return from;
    return to_lambda(
        from, elliptic_crossing(start, strength.sigma0, strength.tau0, mu(), to - from), to);
  }

  // <sigma_n>+ and tau raise f, and the strength tau0 + mu_i <-sigma_n>+ falls as sigma_n
  // grows.
  bool index_grows_with_stress() const override { return true; }

  double rank(double normal_ratio, double shear_ratio_squared) const override {
    return normal_ratio * normal_ratio + shear_ratio_squared;
  }

 private:
  double mu() const { return parameters().internal_friction; }
};

}  // namespace

std::unique_ptr<FailureCriterion> make_elliptic(const CriterionParameters& parameters) {
  return std::make_unique<Elliptic>(parameters);
}

}  // namespace latfrac
