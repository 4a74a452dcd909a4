// A small RunResult with every field set, and a scratch directory, for the [io] tests.
#pragma once

#include <filesystem>
#include <random>
#include <string>

#include "latfrac/fracture/run_result.h"

namespace latfrac::testing {

// 5 nodes in the x-z plane, 4 bonds, 3 break events, 2 snapshots; no field at its default,
// and a problem text longer than the 64 KiB an HDF5 attribute header can hold inline.
inline RunResult sample_result() {
  RunResult result;
  result.provenance = {"latfrac-test",
                       "1.2.3",
                       "0123abcd",
                       "latfrac run graben.toml -o out",
                       "name = \"graben\"\n# λ ≥ 0, σ₀ = 50 MPa\n" + std::string(100000, 'x'),
                       "2024-05-01T12:34:56Z",
                       18446744073709551557ull};
  result.scene = {"graben-2d", 2, 250.0, "elliptic", 2000.0, "the paper's model"};
  result.positions = {0, 0, 0, 250, 0, 0, 500, 0, 0, 0, 0, 250, 250, 0, 250.125};
  result.bonds = {0, 1, 1, 2, 0, 3, 1, 4};
  result.bond_kind = {0, 0, 1, -1};
  result.events = {{1e-4, 2, 1.0000001, BreakMode::tensile, 0},
                   {1e-4, 3, 0.99999, BreakMode::shear, 0},
                   {2.5e-3, 1, 1.5, BreakMode::precut, 7}};
  Snapshot first;
  first.lambda = 1e-4;
  first.displacement = {-0.1, 0, 0, 0, 0, 0, 0.1, 0, 0, -0.1, 0, -1e-9, 0, 0, 3e-300};
  first.bond_intact = {1, 1, 0, 0};
  first.bond_failure_index = {0.5, 0.25, 1.0000001, 0.99999};
  first.node_stress.resize(30);
  for (std::size_t i = 0; i < first.node_stress.size(); ++i) first.node_stress[i] = 1e6 * i - 7e6;
  Snapshot second = first;
  second.lambda = 2.5e-3;
  second.bond_intact = {1, 0, 0, 0};
  second.displacement[0] = -2.5;
  second.node_stress[29] = -0.0;
  result.snapshots = {first, second};
  result.summary.breaks = 3;
  result.summary.final_lambda = 2.5e-3;
  result.summary.wall_seconds = 0.75;
  result.summary.solves = 42;
  result.summary.factorizations = 5;
  result.summary.factor_updates = 37;
  result.summary.floor_acceptances = 2;
  return result;
}

// A fresh directory under the system's temporary directory, removed with its contents.
class ScratchDirectory final {
 public:
  ScratchDirectory() {
    std::random_device random;
    path_ = std::filesystem::temp_directory_path() /
            ("latfrac-io-test-" + std::to_string(random()) + std::to_string(random()));
    std::filesystem::create_directories(path_);
  }
  ~ScratchDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;

  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

}  // namespace latfrac::testing
