// The active-set iteration over switching pairs at one lambda, with its cycle rule.
#include "latfrac/fracture/pair_settling.h"

#include "latfrac/base/phase_times.h"

namespace latfrac {

std::string closed_pairs(const Model& model) {
  std::string closed(model.lattice.bond_count(), '\0');
  for (std::int64_t b = 0; b < model.lattice.bond_count(); ++b) {
    if (!model.contact_capable(b)) continue;
    closed[b] = static_cast<char>(model.law_of(b)->cycle_code(model.springs(b), model.state(b)));
  }
  return closed;
}

void PairSettling::settle(double lambda) {
  const ScopedPhase phase(Phase::contacts);
  const Model& model = equilibrium_.model();
  if (!model.has_contact()) return;
  std::set<std::string> visited;
  for (;;) {
    const Vector u = equilibrium_.displacement(lambda);
    std::vector<PairChange> switches;
    for (std::int64_t b = 0; b < model.lattice.bond_count(); ++b) {
      if (!model.contact_capable(b)) continue;
      const PairTarget wanted = model.law_of(b)->settled_state(model.springs(b), model.state(b),
                                                               model.bond_displacement(u, b));
      if (wanted.state == model.state(b)) continue;
      if (wanted.state == PairState::closed && slides(model.state(b)) && held_.contains(b)) continue;
      switches.push_back({b, wanted.state, wanted.direction});
    }
    if (switches.empty()) return;
    const bool cycling = !visited.insert(closed_pairs(model)).second;
    if (cycling) {
      std::erase_if(switches, [](const PairChange& s) { return s.state != PairState::closed; });
      ++cycles_;
      if (switches.empty()) return;
    }
    for (const PairChange& s : switches)
      if (s.state == PairState::closed && slides(model.state(s.bond))) sticks_.push_back({s.bond, lambda});
    equilibrium_.change_pairs(switches, lambda, u);
    if (cycling) return;
  }
}

}  // namespace latfrac
