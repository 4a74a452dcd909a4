// The event loop: from one event to the next along affine paths, whatever the events are.
#pragma once

#include <functional>
#include <vector>

#include "latfrac/fracture/equilibrium_state.h"
#include "latfrac/fracture/event_source.h"

namespace latfrac {

// Follows the equilibrium path from `from` to `to`. On the affine path of the current
// model every source proposes its first event; the earliest is taken (ties: the source
// listed first), and the loop goes on from there; with no event left it reaches `to`.
// The sources are asked last to first, each told the earliest event so far, so that a
// costly search listed first (the breaks) need only look up to a cheap one's (a contact
// switch).
// Before moving to a lambda, snapshots_before(lambda) takes the snapshots due before it
// (on the path they lie on); after each step, after_step(lambda) reports progress.
void follow_events(EquilibriumState& equilibrium, const std::vector<EventSource*>& sources,
                   double from, double to, const std::function<void(double)>& snapshots_before,
                   const std::function<void(double)>& after_step);

}  // namespace latfrac
