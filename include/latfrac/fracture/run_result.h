// What a run produces: the data written to and read back from a result file.
//
// Arrays are flat and row-major so they map one-to-one onto the HDF5 datasets of
// ../docs/result-files.md: positions N x 3, bonds M x 2, node_stress N x 6 (xx yy zz yz xz
// xy, Pa, tension positive), displacement N x 3 (m).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "latfrac/base/phase_times.h"
#include "latfrac/criteria/stress.h"

namespace latfrac {

struct Provenance {
  std::string software = "latfrac";
  std::string version;
  std::string git_commit;
  std::string command_line;
  std::string problem;  // full problem-file text
  std::string created;  // ISO 8601
  std::uint64_t seed = 0;
};

// Scene facts a reader needs to interpret the arrays (and draw them).
struct SceneInfo {
  std::string name;
  int dim = 2;
  double spacing = 0;       // m
  std::string criterion;    // "" for an elastic scene
  double exaggeration = 1;  // for pictures
  std::string model;        // which of the two models (model_label); empty: not recorded
};

struct BreakEvent {
  double lambda = 0;
  std::int64_t bond = 0;
  double failure_index = 0;
  BreakMode mode = BreakMode::tensile;  // in the file: 0 tensile, 1 shear, 2 pre-cut
  std::int64_t cascade = 0;
};

// A part of the body that lost its support and was held along the axes it lacked.
struct FragmentEvent {
  double lambda = 0;
  std::int64_t nodes = 0;
};

struct Snapshot {
  double lambda = 0;
  std::vector<double> displacement;        // N x 3, m
  std::vector<std::uint8_t> bond_intact;   // M
  std::vector<double> bond_failure_index;  // M ("bond_f" in the file)
  std::vector<double> node_stress;         // N x 6, Pa
};

// What a run counted: the fracture run and the solvers fill it, the result file's
// /summary holds it.
struct RunCounters {
  std::int64_t breaks = 0;
  std::int64_t solves = 0;          // back-substitutions (and relaxation solves)
  std::int64_t factorizations = 0;  // numeric factorizations
  std::int64_t factor_updates = 0;  // rank updates of the factor
  std::int64_t contact_cycles = 0;  // contact iterations that cycled and were resolved
  std::int64_t relaxation_sweeps = 0;       // solver.method = "relaxation": sweeps in all
  std::int64_t relaxation_unconverged = 0;  // relaxation solves stopped by the sweep cap
  // Solutions accepted at the rounding floor, above solver.tolerance (docs/robustness.md).
  std::int64_t floor_acceptances = 0;
};

struct RunSummary : RunCounters {
  double final_lambda = 0;  // the total; in an incomplete file, the lambda reached
  // With friction: the slip of every contact summed (m) and the work friction dissipated
  // (J; 2-D: J per metre), over the whole run.
  double contact_slip = 0;
  double friction_work = 0;
  double wall_seconds = 0;
  bool complete = true;  // false while the run is going on, or when it stopped
  // Where this process's wall time went, s per part (base/phase_times.h): all zero when
  // not measured (a result read from a file: the split is not stored in it).
  std::array<double, phase_count> phase_seconds{};
};

struct RunResult {
  Provenance provenance;
  SceneInfo scene;
  std::vector<double> positions;       // N x 3, m
  std::vector<std::int64_t> bonds;     // M x 2
  std::vector<std::int8_t> bond_kind;  // M: 0 nearest, 1 next-nearest
  std::vector<BreakEvent> events;
  std::vector<FragmentEvent> fragments;
  std::vector<Snapshot> snapshots;
  // With friction, per bond at the end of the run (empty without): the slip its contact
  // accumulated (m) and the work its friction dissipated (J; 2-D: J per metre).
  std::vector<double> contact_slip, friction_work;
  // With contacts along cracks (contact.normal = "crack"), per bond at the end of the run
  // the unit normal its contact acts along (x, y, z; the bond's direction while intact);
  // empty otherwise.
  std::vector<double> contact_normal;
  RunSummary summary;

  std::size_t node_count() const { return positions.size() / 3; }
  std::size_t bond_count() const { return bond_kind.size(); }
  // The extents along x, y and z of the reference positions, m (0 along an axis the
  // lattice does not span, and without nodes).
  std::array<double, 3> extents() const {
    std::array<double, 3> extent{0, 0, 0};
    for (int axis = 0; axis < 3; ++axis) {
      double low = std::numeric_limits<double>::infinity(), high = -low;
      for (std::size_t node = 0; node < node_count(); ++node) {
        low = std::min(low, positions[3 * node + axis]);
        high = std::max(high, positions[3 * node + axis]);
      }
      if (high > low) extent[axis] = high - low;
    }
    return extent;
  }
  // The lattice's size: its largest extent, m (0 without nodes).
  double largest_extent() const {
    const std::array<double, 3> e = extents();
    return std::max({e[0], e[1], e[2]});
  }
  // Bond b's offset in the snapshot: u_j - u_i, its second node's displacement less its
  // first's (x, y, z), m. The fault analysis and the pictures' --min-offset read it.
  std::array<double, 3> bond_offset(const Snapshot& snapshot, std::size_t b) const {
    const std::size_t i = 3 * static_cast<std::size_t>(bonds[2 * b]);
    const std::size_t j = 3 * static_cast<std::size_t>(bonds[2 * b + 1]);
    return {snapshot.displacement[j] - snapshot.displacement[i],
            snapshot.displacement[j + 1] - snapshot.displacement[i + 1],
            snapshot.displacement[j + 2] - snapshot.displacement[i + 2]};
  }
  // Its smallest extent over the axes it spans (x and z in 2-D), m (0 without nodes): a
  // motion beyond it is beyond small strain, however long the body is.
  double smallest_extent() const {
    double size = 0;
    for (const double e : extents())
      if (e > 0) size = size > 0 ? std::min(size, e) : e;
    return size;
  }
};

}  // namespace latfrac
