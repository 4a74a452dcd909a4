// The constructors the registry (criterion.cpp) knows: one per criterion file.
#pragma once

#include <memory>

#include "latfrac/criteria/criterion.h"

namespace latfrac {

std::unique_ptr<FailureCriterion> make_tensile(const CriterionParameters& parameters);
std::unique_ptr<FailureCriterion> make_tensile_or_shear(const CriterionParameters& parameters);
std::unique_ptr<FailureCriterion> make_elliptic(const CriterionParameters& parameters);
std::unique_ptr<FailureCriterion> make_drucker_prager(const CriterionParameters& parameters);

}  // namespace latfrac
