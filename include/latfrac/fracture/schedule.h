// The loading schedule of a fracture run: how far lambda goes, how it steps, and where
// snapshots are taken.
#pragma once

#include <vector>

namespace latfrac {

enum class SteppingMethod { event, fixed };

struct Stepping {
  SteppingMethod method = SteppingMethod::event;
  double increment = 0;  // strain increment ds for the fixed-step method
};

struct Schedule {
  double total = 0;               // the final extension strain lambda (negative: compression)
  Stepping stepping;
  std::vector<double> snapshots;  // lambdas at which to store a snapshot (none: the end)
};

}  // namespace latfrac
