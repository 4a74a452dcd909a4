// The criteria called by name, as the tests ask for them: each call goes through the
// criterion object the registry makes (make_criterion), so the tests check those objects.
#pragma once

#include "latfrac/criteria/criterion.h"
#include "latfrac/criteria/drucker_prager.h"

namespace latfrac::testing {

// The criterion object of `criterion` in `dim` dimensions. Its strengths come with each
// call; the friction angle (30 deg) only sets Drucker-Prager's constants, which the tests
// below never use through this helper.
// internal_friction (mu_i) makes the shear strength tau0 + mu_i <-sigma_n>+.
inline std::shared_ptr<const FailureCriterion> criterion_object(Criterion criterion, int dim = 2,
                                                                double internal_friction = 0) {
  Strength strength;
  strength.criterion = criterion;
  strength.sigma0 = 1;
  strength.friction_angle = 30;
  strength.internal_friction = internal_friction;
  return make_criterion(strength, dim);
}

inline FailureIndex failure_index(Criterion criterion, double sigma_n, double tau, double sigma0,
                                  double tau0, double internal_friction = 0) {
  return criterion_object(criterion, 2, internal_friction)->index(sigma_n, tau, {sigma0, tau0});
}

inline FailureIndex critical_plane_index(Criterion criterion, const VoigtStress& stress, int dim,
                                         double sigma0, double tau0, double internal_friction = 0) {
  return criterion_object(criterion, dim, internal_friction)->tensor_index(stress, {sigma0, tau0});
}

inline double first_crossing(Criterion criterion, const AffineBondStress& stress, double sigma0,
                             double tau0, double from, double to, double internal_friction = 0) {
  return criterion_object(criterion, 2, internal_friction)
      ->first_crossing(stress, {sigma0, tau0}, from, to);
}

}  // namespace latfrac::testing
