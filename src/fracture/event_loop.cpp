// The event loop over event sources.
#include "latfrac/fracture/event_loop.h"

#include <cmath>

namespace latfrac {

void follow_events(EquilibriumState& equilibrium, const std::vector<EventSource*>& sources,
                   double from, double to, const std::function<void(double)>& snapshots_before,
                   const std::function<void(double)>& after_step) {
  double lambda = from;
  while (lambda != to) {
    const AffinePath& path = equilibrium.path(lambda);
    // Asked last to first, each with the earliest event so far as the bound of what it
    // need find: a source listed earlier wins a tie, so it takes an equal lambda too.
    EventSource* first = nullptr;
    double next = to;
    for (auto source = sources.rbegin(); source != sources.rend(); ++source) {
      const double proposed =
          (*source)->propose(path, lambda, to, first ? next : EventSource::none);
      if (std::isnan(proposed)) continue;
      if (!first || std::abs(proposed) <= std::abs(next)) {
        first = *source;
        next = proposed;
      }
    }
    snapshots_before(next);
    for (EventSource* source : sources) source->reached(next);
    lambda = next;
    if (first) first->take(lambda);
    after_step(lambda);
  }
}

}  // namespace latfrac
