// Test helpers for the hard cases: quiet runs, finiteness, and the equilibrium of a final
// state checked part by part on a freshly built model, independently of the run.
#pragma once

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <vector>

#include "final_state.h"
#include "latfrac/scene/run.h"

namespace latfrac::testing {


inline RunOptions quiet() {
  RunOptions options;
  options.progress = false;
  return options;
}

inline bool all_finite(const std::vector<double>& values) {
  return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

inline bool snapshots_finite(const RunResult& result) {
  for (const Snapshot& s : result.snapshots) {
    if (!all_finite(s.displacement) || !all_finite(s.node_stress) ||
        !all_finite(s.bond_failure_index))
      return false;
  }
  return true;
}

// Equilibrium of a final state, part by part. The connected parts (intact bonds) are found
// here, independently of the run. A part with no prescribed dof along an axis in the fresh
// model must have been held along it by the run (docs/robustness.md): the force on those
// dofs is the holding force. Everywhere else the residual must vanish.
struct Balance {
  double relative_residual =
      0;  // max |R| over the free dofs of supported parts / max |R(0, lambda)|
  double support_reaction = 0;  // vertical reactions of the prescribed dofs (N), upward positive
  double holding_force = 0;     // vertical forces that hold parts without vertical support
  double weight = 0;            // total gravity force (N), positive
  std::int64_t held_nodes = 0;  // nodes of parts without support along some axis
};

// The parts connected through intact bonds: each node's part, and per part whether one of
// its nodes has a prescribed dof along each axis.
struct SupportedParts {
  std::vector<std::int64_t> part;               // per node
  std::vector<std::array<bool, 3>> supported;  // per part and axis
};

inline SupportedParts supported_parts(const Model& model) {
  const Lattice& lattice = model.lattice;
  const int dim = model.dim();
  const std::int64_t nodes = lattice.node_count();
  std::vector<std::vector<std::int64_t>> neighbours(nodes);
  for (std::int64_t b = 0; b < lattice.bond_count(); ++b) {
    if (!model.intact(b)) continue;
    neighbours[lattice.bonds[b].i].push_back(lattice.bonds[b].j);
    neighbours[lattice.bonds[b].j].push_back(lattice.bonds[b].i);
  }
  SupportedParts parts{std::vector<std::int64_t>(nodes, -1), {}};
  for (std::int64_t start = 0; start < nodes; ++start) {
    if (parts.part[start] >= 0) continue;
    const std::int64_t id = static_cast<std::int64_t>(parts.supported.size());
    parts.supported.push_back({false, false, false});
    std::vector<std::int64_t> queue{start};
    parts.part[start] = id;
    for (std::size_t k = 0; k < queue.size(); ++k) {
      const std::int64_t n = queue[k];
      for (int c = 0; c < dim; ++c)
        parts.supported[id][c] =
            parts.supported[id][c] || model.dofs().free_index[n * dim + c] < 0;
      for (std::int64_t next : neighbours[n]) {
        if (parts.part[next] < 0) {
          parts.part[next] = id;
          queue.push_back(next);
        }
      }
    }
  }
  return parts;
}

inline Balance balance(const FinalState& state) {
  const Model& model = state.model;
  const int dim = model.dim();
  const std::int64_t nodes = model.lattice.node_count();
  const auto [part, supported] = supported_parts(model);
  const Vector force = model.internal_force(state.displacement) - model.external_force;
  const Vector unloaded = model.residual(Vector::Zero(model.dofs().free_count), state.lambda);
  // A prestressed body's weight and prestress balance at rest: its scale is the weight.
  const double load = std::max(max_abs(unloaded), model.has_prestress()
                                                      ? max_abs(model.free_part(model.external_force))
                                                      : 0.0);
  Balance result;
  double worst = 0;
  std::vector<std::uint8_t> held(nodes, 0);
  for (std::int64_t n = 0; n < nodes; ++n) {
    for (int c = 0; c < dim; ++c) {
      const std::int64_t dof = n * dim + c;
      const bool vertical = c == dim - 1;
      if (vertical) result.weight -= model.external_force[dof];
      if (model.dofs().free_index[dof] < 0) {
        if (vertical) result.support_reaction += force[dof];
      } else if (supported[part[n]][c]) {
        worst = std::max(worst, std::abs(force[dof]));
      } else {
        held[n] = 1;
        if (vertical) result.holding_force += force[dof];
      }
    }
  }
  result.held_nodes = std::count(held.begin(), held.end(), 1);
  result.relative_residual = load > 0 ? worst / load : worst;
  return result;
}

inline void check_same_events(const RunResult& a, const RunResult& b) {
  REQUIRE(a.events.size() == b.events.size());
  for (std::size_t k = 0; k < a.events.size(); ++k) {
    INFO("event " << k);
    CHECK(a.events[k].bond == b.events[k].bond);
    CHECK(a.events[k].lambda == b.events[k].lambda);
    CHECK(a.events[k].failure_index == b.events[k].failure_index);
    CHECK(a.events[k].mode == b.events[k].mode);
    CHECK(a.events[k].cascade == b.events[k].cascade);
  }
  REQUIRE(a.fragments.size() == b.fragments.size());
  for (std::size_t k = 0; k < a.fragments.size(); ++k) {
    CHECK(a.fragments[k].lambda == b.fragments[k].lambda);
    CHECK(a.fragments[k].nodes == b.fragments[k].nodes);
  }
}

// The final state is in equilibrium where nothing is held, and the supports plus the
// holding forces carry the whole weight.
inline void check_final_equilibrium(const Scene& scene, const RunResult& result, double tolerance = 1e-9) {
  REQUIRE(!result.snapshots.empty());
  const FinalState state = final_state(scene, result);
  const Balance b = balance(state);
  INFO("relative residual " << b.relative_residual << ", support " << b.support_reaction
                            << " N, holding " << b.holding_force << " N, weight " << b.weight
                            << " N, held nodes " << b.held_nodes << ", parts held "
                            << result.fragments.size());
  CHECK(b.relative_residual <= tolerance);
  if (result.fragments.empty()) CHECK(b.held_nodes == 0);
  if (scene.gravity) {
    CHECK(b.support_reaction + b.holding_force == Approx(b.weight).epsilon(1e-9));
    if (b.held_nodes == 0) CHECK(b.support_reaction == Approx(b.weight).epsilon(1e-9));
  }
}

}  // namespace latfrac::testing
