// Event sources: each kind of event on the loading path proposes its earliest occurrence.
//
// Between events the equilibrium path is affine (a linear law and a fixed set of pair
// states). The event loop (event_loop.h) asks every source for its first event after
// the current lambda on that path, moves to the earliest (ties: the source listed first),
// and lets that source take it. A source keeps what it proposed until it is asked to take
// it. A new kind of event (a contact that starts to slip, say) is a new EventSource, added
// to the list the loop is given; the loop itself does not change.
#pragma once

#include <limits>

#include "latfrac/solvers/equilibrium.h"

namespace latfrac {

class EventSource {
 public:
  virtual ~EventSource() = default;
  // The lambda of this source's first event on `path` after `from`, no later than `to`;
  // NaN when there is none. An event after needed_until (NaN: none given) cannot be taken,
  // since another source's comes first: the source may then return any later lambda, or
  // NaN, and save the search.
  virtual double propose(const AffinePath& path, double from, double to, double needed_until) = 0;
  // The loop has moved to lambda (whichever source's event it is, or the end).
  virtual void reached(double /*lambda*/) {}
  // Takes the event this source proposed last, at its lambda: changes the model,
  // re-equilibrates, and runs the cascade that follows.
  virtual void take(double lambda) = 0;

  static constexpr double none = std::numeric_limits<double>::quiet_NaN();
};

// The full displacement along an affine path: at lambda = 0 and per unit lambda.
struct FullPath {
  Vector at_zero, per_lambda;
};
FullPath full_path(const Model& model, const AffinePath& path);

}  // namespace latfrac
