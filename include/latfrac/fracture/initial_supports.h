// The start of a run: contacts closed where pre-cut faces touch, loose parts held.
#pragma once

#include <string>
#include <vector>

#include "latfrac/fracture/run_result.h"
#include "latfrac/mechanics/model.h"

namespace latfrac {

// With contact, the springs of contact-capable bonds start closed (the faces of a
// pre-cut touch at rest; the first settling opens those in tension). Then every part
// without support along some axis is held there at zero displacement. Returns one
// fragment event per held part. Throws InputError, naming source_path, when the face
// conditions leave the whole body free along an axis. Call it before building a solver.
std::vector<FragmentEvent> prepare_supports(Model& model, const std::string& source_path);

}  // namespace latfrac
