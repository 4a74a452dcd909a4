// Pre-cuts: which bonds a cut severs, against a brute-force count on the node positions.
#include "latfrac/geometry/precut.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <set>

using namespace latfrac;

namespace {

using Ids = std::vector<std::int64_t>;

// The bonds whose ends lie on opposite sides of the plane X[axis] = level and whose
// meeting point with it passes `within`: computed from positions alone.
Ids straddling(
    const Lattice& lattice, int axis, double level,
    const std::function<bool(const Vec3&)>& within = [](const Vec3&) { return true; }) {
  Ids ids;
  for (std::int64_t b = 0; b < lattice.bond_count(); ++b) {
    const Vec3& p = lattice.positions[lattice.bonds[b].i];
    const Vec3& q = lattice.positions[lattice.bonds[b].j];
    if ((p[axis] - level) * (q[axis] - level) >= 0) continue;
    const Vec3 meeting = p + (level - p[axis]) / (q[axis] - p[axis]) * (q - p);
    if (within(meeting)) ids.push_back(b);
  }
  return ids;
}

Precut segment(double x1, double z1, double x2, double z2) {
  Precut cut;
  cut.from = {x1, 0, z1};
  cut.to = {x2, 0, z2};
  return cut;
}

Precut rectangle(const Vec3& corner, const Vec3& edge1, const Vec3& edge2) {
  Precut cut;
  cut.corner = {corner.x(), corner.y(), corner.z()};
  cut.edge1 = {edge1.x(), edge1.y(), edge1.z()};
  cut.edge2 = {edge2.x(), edge2.y(), edge2.z()};
  return cut;
}

int row_count(const Lattice& lattice) {
  std::set<long> rows;
  for (const Vec3& p : lattice.positions) rows.insert(std::lround(p.z() / lattice.row_pitch));
  return static_cast<int>(rows.size());
}

const Lattice& lattice_2d() {
  static const Lattice lattice = build_lattice({2, 1.0, {10.0, 0.0, 6.0}, true});
  return lattice;
}

const Lattice& lattice_3d() {
  static const Lattice lattice = build_lattice({3, 1.0, {6.0, 4.0, 5.0}, true});
  return lattice;
}

}  // namespace

TEST_CASE("2-D: a vertical cut between nodes severs the bonds that straddle it", "[precut]") {
  const Lattice& lattice = lattice_2d();
  const double x_cut = 5.25, top = lattice.extent.z();  // nodes sit at multiples of a/2

  // Every row holds one horizontal bond across x_cut (5 - 6 or 4.5 - 5.5); every gap
  // between rows one diagonal (5 - 5.5): the other diagonals end on one side.
  const Ids full = bonds_crossing_precuts(lattice, {segment(x_cut, top + 1, x_cut, -1)});
  const int rows = row_count(lattice);
  CHECK(full.size() == static_cast<std::size_t>(2 * rows - 1));
  CHECK(full == straddling(lattice, 0, x_cut));

  // Down to 2.1 row pitches: only the bonds that meet x = x_cut at or above that height.
  const double bottom = 2.1 * lattice.row_pitch;
  const Ids partial = bonds_crossing_precuts(lattice, {segment(x_cut, top + 1, x_cut, bottom)});
  CHECK(partial == straddling(lattice, 0, x_cut, [&](const Vec3& m) { return m.z() >= bottom; }));
  // Rows 3 and up: their horizontals, and the diagonals above row 2 (they meet x_cut
  // half-way between rows, at 2.5, 3.5, ... row pitches).
  CHECK(partial.size() == 2u * (rows - 3));
}

TEST_CASE("2-D: a cut through a column of nodes cuts nothing on the rows of those nodes",
          "[precut]") {
  const Lattice& lattice = lattice_2d();
  const double x_cut = 5.0;  // on the nodes of the even rows
  const Ids cut =
      bonds_crossing_precuts(lattice, {segment(x_cut, lattice.extent.z() + 1, x_cut, -1)});
  // Only the horizontal bond 4.5 - 5.5 of each odd row: every other bond touching x = 5
  // has an end on the cut, and touching is not crossing.
  CHECK(cut.size() == static_cast<std::size_t>(row_count(lattice) / 2));
  for (std::int64_t b : cut) {
    const Vec3& p = lattice.positions[lattice.bonds[b].i];
    const Vec3& q = lattice.positions[lattice.bonds[b].j];
    CHECK(p.z() == q.z());
    CHECK(std::lround(p.z() / lattice.row_pitch) % 2 == 1);
  }
}

TEST_CASE("a cut of zero length or area, or outside the body, cuts nothing", "[precut]") {
  const Lattice& flat = lattice_2d();
  const double top = flat.extent.z();
  CHECK(bonds_crossing_precuts(flat, {}).empty());
  CHECK(bonds_crossing_precuts(flat, {segment(5.25, 3.0, 5.25, 3.0)}).empty());
  CHECK(bonds_crossing_precuts(flat, {segment(20.0, 1.0, 20.0, 5.0)}).empty());
  CHECK(bonds_crossing_precuts(flat, {segment(1.0, top + 0.5, 9.0, top + 0.5)}).empty());

  const Lattice& block = lattice_3d();
  const Vec3 corner(3.25, -1, -1), across(0, 10, 0), down(0, 0, 10);
  CHECK(bonds_crossing_precuts(block, {rectangle(corner, Vec3::Zero(), down)}).empty());
  CHECK(bonds_crossing_precuts(block, {rectangle(corner, across, 2 * across)}).empty());
  CHECK(bonds_crossing_precuts(block, {rectangle(Vec3(20, -1, -1), across, down)}).empty());
}

TEST_CASE("3-D: a vertical rectangle through the full width severs the straddling bonds",
          "[precut]") {
  const Lattice& lattice = lattice_3d();
  const Vec3& extent = lattice.extent;
  const double x_cut = 3.25;  // HCP nodes sit at multiples of a/2 along x
  const Ids full = bonds_crossing_precuts(
      lattice,
      {rectangle(Vec3(x_cut, -1, -1), Vec3(0, extent.y() + 2, 0), Vec3(0, 0, extent.z() + 2))});
  CHECK(full == straddling(lattice, 0, x_cut));
  int next_nearest = 0;
  for (std::int64_t b : full) next_nearest += lattice.bonds[b].kind == BondKind::next_nearest;
  CHECK(next_nearest > 0);
  CHECK(next_nearest < static_cast<int>(full.size()));

  const double bottom = 1.7 * lattice.row_pitch;
  const Ids partial = bonds_crossing_precuts(
      lattice, {rectangle(Vec3(x_cut, -1, bottom), Vec3(0, extent.y() + 2, 0),
                          Vec3(0, 0, extent.z() + 1 - bottom))});
  CHECK(partial == straddling(lattice, 0, x_cut, [&](const Vec3& m) { return m.z() >= bottom; }));
  CHECK(!partial.empty());
  CHECK(partial.size() < full.size());
}

TEST_CASE("3-D: a horizontal rectangle between layers severs the straddling bonds", "[precut]") {
  const Lattice& lattice = lattice_3d();
  const Vec3& extent = lattice.extent;
  const double z_cut = 2.5 * lattice.row_pitch;
  const Ids full = bonds_crossing_precuts(
      lattice,
      {rectangle(Vec3(-1, -1, z_cut), Vec3(extent.x() + 2, 0, 0), Vec3(0, extent.y() + 2, 0))});
  CHECK(full == straddling(lattice, 2, z_cut));
  CHECK(!full.empty());

  // A patch: x in [1.2, 3.7], y in [0.6, 2.9], edges given in the other order.
  const Ids patch = bonds_crossing_precuts(
      lattice, {rectangle(Vec3(1.2, 0.6, z_cut), Vec3(0, 2.3, 0), Vec3(2.5, 0, 0))});
  CHECK(patch == straddling(lattice, 2, z_cut, [](const Vec3& m) {
          return m.x() >= 1.2 && m.x() <= 3.7 && m.y() >= 0.6 && m.y() <= 2.9;
        }));
  CHECK(!patch.empty());
  CHECK(patch.size() < full.size());
}

TEST_CASE("two cuts that meet end to end sever what the joined cut severs, in any order",
          "[precut]") {
  const Lattice& flat = lattice_2d();
  const double top = flat.extent.z() + 1, joint = 3 * flat.row_pitch;  // joint on row 3
  const Precut upper = segment(5.25, top, 5.25, joint), lower = segment(5.25, joint, 5.25, -1);
  const Ids joined = bonds_crossing_precuts(flat, {segment(5.25, top, 5.25, -1)});
  CHECK(bonds_crossing_precuts(flat, {upper, lower}) == joined);
  CHECK(bonds_crossing_precuts(flat, {lower, upper}) == joined);
  // Row 3's horizontal bond meets the cut exactly at the joint: both halves sever it.
  const Ids from_upper = bonds_crossing_precuts(flat, {upper});
  const Ids from_lower = bonds_crossing_precuts(flat, {lower});
  std::set<std::int64_t> shared;
  for (std::int64_t b : from_upper) {
    if (std::count(from_lower.begin(), from_lower.end(), b)) shared.insert(b);
  }
  CHECK(shared.size() == 1);

  const Precut slanted_a = segment(1.3, 0.2, 4.55, 2.6), slanted_b = segment(4.55, 2.6, 7.8, 5.0);
  CHECK(bonds_crossing_precuts(flat, {slanted_b, slanted_a}) ==
        bonds_crossing_precuts(flat, {segment(1.3, 0.2, 7.8, 5.0)}));

  const Lattice& block = lattice_3d();
  const Vec3 across(0, block.extent.y() + 2, 0);
  const double low = -1, mid = 2 * block.row_pitch, high = block.extent.z() + 1;
  const Precut whole = rectangle(Vec3(3.25, -1, low), across, Vec3(0, 0, high - low));
  const Precut below = rectangle(Vec3(3.25, -1, low), across, Vec3(0, 0, mid - low));
  const Precut above = rectangle(Vec3(3.25, -1, mid), across, Vec3(0, 0, high - mid));
  CHECK(bonds_crossing_precuts(block, {above, below}) == bonds_crossing_precuts(block, {whole}));
}
