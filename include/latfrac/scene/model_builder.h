// From a scene to its mechanical model.
#pragma once

#include "latfrac/mechanics/model.h"
#include "latfrac/scene/scene.h"

namespace latfrac {

// Builds the model: lattice, per-bond springs and strengths (layers and heterogeneity
// included), pre-cut bonds broken, the face conditions and gravity. Throws InputError for
// parameters the lattice cannot represent.
Model build_model(const Scene& scene);

}  // namespace latfrac
