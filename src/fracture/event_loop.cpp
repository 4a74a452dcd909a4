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
    EventSource* first = nullptr;
    double next = to;
    for (EventSource* source : sources) {
      const double proposed = source->propose(path, lambda, to);
      if (std::isnan(proposed)) continue;
      if (!first || std::abs(proposed) < std::abs(next)) {
        first = source;
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
