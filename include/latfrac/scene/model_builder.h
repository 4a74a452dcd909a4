// From a scene to its mechanical model.
#pragma once

#include "latfrac/criteria/criterion.h"
#include "latfrac/mechanics/model.h"
#include "latfrac/scene/scene.h"

namespace latfrac {

// Builds the model: lattice, per-bond springs and strengths (layers and heterogeneity
// included), pre-cut bonds broken, the face conditions and gravity. Throws InputError for
// parameters the lattice cannot represent.
// The criterion gives the strengths (resolved once, make_criterion); a scene without
// [strength] has none (null).
Model build_model(const Scene& scene, const FailureCriterion* criterion);
// The same with the scene's own criterion, made here.
Model build_model(const Scene& scene);

}  // namespace latfrac
