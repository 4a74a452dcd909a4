// Small scenes built in code for the tests (the problem-file reader has its own tests).
#pragma once

#include "latfrac/base/progress.h"
#include "latfrac/fracture/fracture_run.h"
#include "latfrac/fracture/initial_supports.h"
#include "latfrac/scene/model_builder.h"
#include "latfrac/solvers/equilibrium.h"

namespace latfrac::testing {

// The paper's material: rho 2600 kg/m^3, E 100 GPa, nu 0.2.
inline Material paper_material(double poisson = 0.2) { return {2600.0, 100e9, poisson}; }

inline Scene box_scene(int dim, double spacing, std::array<double, 3> size, bool gravity) {
  Scene scene;
  scene.name = "test";
  scene.lattice.dim = dim;
  scene.lattice.spacing = spacing;
  scene.lattice.size = size;
  scene.material = paper_material();
  if (gravity) scene.gravity = Gravity{9.81};
  return scene;
}

// A [strength] section: the criterion, sigma0 (Pa) and the friction angle psi (degrees)
// from which tau0 is derived with m = 1.
inline Strength strength_of(Criterion criterion, double sigma0, double friction_angle = 30.0) {
  Strength strength;
  strength.criterion = criterion;
  strength.sigma0 = sigma0;
  strength.friction_angle = friction_angle;
  return strength;
}

// Runs the fracture of a model built from `scene` (and changed by the caller, which is what
// run_scene cannot do), holding what the pre-cuts cut loose first. `integrated`: follow
// the paths with CVODE and KINSOL even for a linear law. `screened`: whether event-driven
// crossing searches may be screened (path_screen.h); `searches` gets how many were, and
// how many were made in full beside them.
inline RunResult run_model(Model& model, const Scene& scene, bool integrated = false,
                           bool screened = true, std::int64_t (*searches)[2] = nullptr) {
  prepare_supports(model, scene.source_path);
  EquilibriumSolver solver(model, scene.solver);
  ProgressLine progress(false);
  RunResult result;
  FractureRun fracture(model, make_criterion(*scene.strength, scene.lattice.dim),
                       scene.strength->bond_stress, schedule_of(scene), scene.solver, solver,
                       progress, result);
  fracture.use_integrated_path(integrated);
  fracture.screen_paths(screened);
  fracture.run();
  if (searches) {
    (*searches)[0] = fracture.screened_searches();
    (*searches)[1] = fracture.full_searches();
  }
  return result;
}

}  // namespace latfrac::testing
