// Drucker-Prager on a stress tensor: its failure index and its closed-form crossing.
//
// f = (sqrt(J2) + alpha I1) / k (tension positive); the constants come from
// drucker_prager_constants (criterion.h). The criterion object is in drucker_prager.cpp.
#pragma once

#include "latfrac/criteria/stress.h"

namespace latfrac {

// In 2-D, yy is already nu (xx + zz). The mode is tensile when alpha I1 >= sqrt(J2).
FailureIndex drucker_prager_index(const VoigtStress& stress, double alpha, double k);

// The smallest l in (from, to] with f >= 1 on S(l) = s0 + l s1 (Voigt, Pa); `from` when
// f(from) >= 1; +infinity when none.
double first_crossing_drucker_prager(const VoigtStress& s0, const VoigtStress& s1, double alpha,
                                     double k, double from, double to);

}  // namespace latfrac
