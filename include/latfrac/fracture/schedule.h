// The loading schedule of a fracture run: how far lambda goes, how it steps, and where
// snapshots are taken.
#pragma once

#include <cmath>
#include <vector>

namespace latfrac {

enum class SteppingMethod { event, fixed };

// The most fixed steps a run may take, |total| / increment: 1e9 solves would take days on
// any lattice, and beyond it the step count does not fit the loop's counter either (an
// increment of 1e-300 made a run that took no step and wrote a result with no snapshot).
inline constexpr double max_fixed_steps = 1e9;

// The number of fixed steps from 0 to total: the last may be shorter (it ends at total).
inline long fixed_step_count(double total, double increment) {
  return total == 0 ? 0 : static_cast<long>(std::ceil(std::abs(total) / increment - 1e-9));
}

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
