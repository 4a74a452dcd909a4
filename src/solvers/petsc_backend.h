// The petsc backend's factory (petsc_backend.cpp); linear_backend.cpp calls it.
#pragma once

#include <memory>

#include "latfrac/solvers/linear_backend.h"

namespace latfrac {

// Throws InputError in a build without PETSc.
std::unique_ptr<LinearBackend> make_petsc_backend();

}  // namespace latfrac
