// Lattice geometry: coordination, bond lengths, faces, and rejected boxes.
#include "latfrac/geometry/lattice.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "latfrac/base/error.h"
#include "latfrac/scene/size_estimate.h"

using namespace latfrac;

namespace {

std::vector<int> coordination(const Lattice& lattice, BondKind kind) {
  std::vector<int> count(lattice.node_count(), 0);
  for (const Bond& b : lattice.bonds) {
    if (b.kind != kind) continue;
    ++count[b.i];
    ++count[b.j];
  }
  return count;
}

bool interior(const Lattice& lattice, std::int64_t n, double margin) {
  const Vec3& p = lattice.positions[n];
  for (int axis = 0; axis < 3; ++axis) {
    if (lattice.dim == 2 && axis == 1) continue;
    if (p[axis] < margin || p[axis] > lattice.extent[axis] - margin) return false;
  }
  return true;
}

}  // namespace

TEST_CASE("2-D triangular lattice: interior nodes have six neighbours at a", "[lattice]") {
  LatticeSpec spec{2, 100.0, {2000.0, 0.0, 1000.0}, true};
  const Lattice lattice = build_lattice(spec);
  CHECK(lattice.extent.x() == Approx(2000.0));
  CHECK(lattice.extent.z() ==
        Approx(std::sqrt(3.0) / 2 * 100 * std::lround(1000 / (std::sqrt(3.0) / 2 * 100))));
  const auto count = coordination(lattice, BondKind::nearest);
  int checked = 0;
  for (std::int64_t n = 0; n < lattice.node_count(); ++n) {
    CHECK(lattice.positions[n].y() == 0.0);
    if (!interior(lattice, n, 150.0)) continue;
    CHECK(count[n] == 6);
    ++checked;
  }
  CHECK(checked > 100);
  for (double length : lattice.bond_length) CHECK(length == Approx(100.0).epsilon(1e-12));
  // Nodes within a/2 of x = 0 are on x_min: the first node of every row.
  for (std::int64_t n = 0; n < lattice.node_count(); ++n) {
    CHECK(lattice.on_face(n, Face::x_min) == (lattice.positions[n].x() <= 50.0 + 1e-6));
    CHECK(lattice.on_face(n, Face::z_max) ==
          (lattice.extent.z() - lattice.positions[n].z() < 50.0));
  }
}

TEST_CASE("3-D HCP lattice: 12 nearest neighbours at a and 6 next-nearest at sqrt(2) a",
          "[lattice]") {
  LatticeSpec spec{3, 1.0, {8.0, 8.0, 8.0}, true};
  const Lattice lattice = build_lattice(spec);
  const auto nearest = coordination(lattice, BondKind::nearest);
  const auto next = coordination(lattice, BondKind::next_nearest);
  int checked = 0;
  for (std::int64_t n = 0; n < lattice.node_count(); ++n) {
    if (!interior(lattice, n, 1.6)) continue;
    CHECK(nearest[n] == 12);
    CHECK(next[n] == 6);
    ++checked;
  }
  CHECK(checked > 20);
  for (std::size_t b = 0; b < lattice.bonds.size(); ++b) {
    const double expected = lattice.bonds[b].kind == BondKind::nearest ? 1.0 : std::sqrt(2.0);
    CHECK(lattice.bond_length[b] == Approx(expected).epsilon(1e-12));
  }
  CHECK(lattice.node_volume == Approx(1 / std::sqrt(2.0)));
  // The size estimate that `latfrac check` prints (and `run` uses to refuse problems too
  // large for memory) is close to the lattice actually built.
  Scene scene;
  scene.lattice = spec;
  const SizeEstimate estimate = estimate_size(scene);
  CHECK(std::abs(estimate.nodes - lattice.node_count()) < 0.1 * lattice.node_count());
  // Bonds are counted at the interior's 9 per node: never fewer than the lattice has.
  CHECK(estimate.bonds >= lattice.bond_count());
}

TEST_CASE("Lattices that cannot be built are rejected with a message naming the key", "[lattice]") {
  auto message_of = [](LatticeSpec spec) {
    try {
      build_lattice(spec);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK_THAT(message_of({2, -1.0, {10, 0, 10}, true}), Catch::Contains("lattice.spacing"));
  CHECK_THAT(message_of({2, 0.0, {10, 0, 10}, true}), Catch::Contains("positive"));
  CHECK_THAT(message_of({2, 1.0, {-5, 0, 10}, true}), Catch::Contains("lattice.size"));
  CHECK_THAT(message_of({2, 1.0, {1.5, 0, 10}, true}),
             Catch::Contains("smaller than two spacings"));
  CHECK_THAT(message_of({3, 1.0, {10, 1.0, 10}, true}), Catch::Contains("y extent"));
  CHECK_THAT(message_of({4, 1.0, {10, 10, 10}, true}), Catch::Contains("lattice.dim"));
}

TEST_CASE("Sizes print in readable units, three digits, never in exponent form", "[lattice]") {
  const double mib = 1024.0 * 1024.0;
  CHECK(readable_bytes(512 * mib) == "512 MiB");
  CHECK(readable_bytes(3.2 * 1024 * mib) == "3.2 GiB");
  // 1010 MiB is 0.986 GiB (1010 / 1024 = 0.98633): with three digits 1010 would print
  // as 1.01e+03.
  CHECK(readable_bytes(1010 * mib) == "0.986 GiB");
  CHECK(readable_bytes(999 * mib) == "999 MiB");
}
