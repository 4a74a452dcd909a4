// The threaded sweeps over the bonds: the same numbers bit for bit on any number of
// threads, and the same as the serial loop over the bonds (docs/model.md, "Threads").
#include "latfrac/base/threads.h"

#include <atomic>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "latfrac/base/error.h"
#include "latfrac/io/problem_file.h"
#include "latfrac/mechanics/node_stress.h"
#include "latfrac/scene/run.h"
#include "scenes.h"

using namespace latfrac;
using namespace latfrac::testing;

namespace {

// Sets the sweeps' thread count for one scope, then back to LATFRAC_THREADS's (CTest sets
// it to 1) or the cores'.
struct ThreadCount {
  explicit ThreadCount(int n) { threads::set_count(n); }
  ~ThreadCount() { threads::set_count(0); }
};

// A random 2-D section of about 12 500 bonds and 4200 nodes (enough for two threads: 4096
// bonds and 2048 nodes each at least), a tenth of its bonds broken, and a random
// displacement field.
struct Sample {
  Model model;
  Vector u, rate;
};

Sample sample() {
  Scene scene = box_scene(2, 250.0, {25e3, 0, 9e3}, true);
  scene.lattice.kind = LatticeKind::random;
  scene.lattice.seed = 3;
  Sample s{build_model(scene), {}, {}};
  ModelEditor editor(s.model);
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (std::int64_t b = 0; b < s.model.lattice.bond_count(); b += 10)
    editor.set_state(b, PairState::open);
  const std::int64_t dofs = s.model.dofs().dof_count();
  s.u = Vector::NullaryExpr(dofs, [&] { return unit(random); });
  s.rate = Vector::NullaryExpr(dofs, [&] { return unit(random); });
  return s;
}

}  // namespace

TEST_CASE("for_blocks covers every item once, in disjoint blocks, and rethrows", "[threads]") {
  const ThreadCount three(3);
  const std::int64_t items = 10007;
  std::vector<std::atomic<int>> visits(items);
  std::atomic<int> blocks = 0;
  threads::for_blocks(items, 1, [&](std::int64_t first, std::int64_t last) {
    ++blocks;
    for (std::int64_t k = first; k < last; ++k) ++visits[k];
  });
  for (const auto& v : visits) REQUIRE(v == 1);
  CHECK(blocks == 12);  // four per thread
  // Fewer items than the grain asks for: the calling thread alone, one block.
  blocks = 0;
  threads::for_blocks(100, 64, [&](std::int64_t first, std::int64_t last) {
    ++blocks;
    CHECK(first == 0);
    CHECK(last == 100);
  });
  CHECK(blocks == 1);
  REQUIRE_THROWS_AS(threads::for_blocks(items, 1,
                                        [&](std::int64_t first, std::int64_t last) {
                                          if (first <= 5000 && 5000 < last) throw Error("block");
                                        }),
                    Error);
}

TEST_CASE("node_bonds lists each node's bonds in bond order, with the end it is", "[threads]") {
  LatticeSpec spec;
  spec.dim = 2;
  spec.spacing = 1.0;
  spec.size = {4.0, 0.0, 3.0};
  const Lattice lattice = build_lattice(spec);
  const NodeBonds index = node_bonds(lattice);
  REQUIRE(index.node_count() == lattice.node_count());
  std::vector<int> seen(lattice.bond_count(), 0);
  for (std::int64_t n = 0; n < lattice.node_count(); ++n) {
    std::int64_t previous = -1;
    for (std::int64_t k = index.start[n]; k < index.start[n + 1]; ++k) {
      const std::int64_t b = index.entries[k] / 2;
      const Bond& bond = lattice.bonds[b];
      CHECK(b > previous);
      previous = b;
      CHECK((index.entries[k] % 2 == 1 ? bond.j : bond.i) == n);
      ++seen[b];
    }
  }
  for (int count : seen) CHECK(count == 2);
}

TEST_CASE("threaded sweeps give the serial loop's numbers bit for bit", "[threads]") {
  const Sample s = sample();
  REQUIRE(s.model.lattice.bond_count() >= 2 * 4096);
  REQUIRE(s.model.lattice.node_count() >= 2 * 2048);
  // The serial definition: each bond's force added to its two ends, in bond order.
  Vector serial = Vector::Zero(s.model.dofs().dof_count());
  for (std::int64_t b = 0; b < s.model.lattice.bond_count(); ++b)
    s.model.add_bond_force(s.u, b, serial);
  std::vector<double> stress[2], zero[2], per_unit[2];
  Vector force[2];
  for (int k = 0; k < 2; ++k) {
    const ThreadCount count(k == 0 ? 1 : 3);
    stress[k] = node_stresses(s.model, s.u);
    const NodeStressPath path = node_stress_path(s.model, s.u, s.rate);
    zero[k] = path.at_zero;
    per_unit[k] = path.per_unit;
    force[k] = s.model.internal_force(s.u);
  }
  CHECK(force[0] == serial);
  CHECK(force[1] == serial);
  CHECK(stress[1] == stress[0]);
  CHECK(zero[1] == stress[0]);  // the path's sweep is node_stresses' at its start
  CHECK(per_unit[1] == per_unit[0]);
  CHECK(per_unit[0] == node_stress_rates(s.model, s.rate));
}

TEST_CASE("node stresses at a few nodes are node_stresses' there, bit for bit", "[threads]") {
  // The sample (gravity, face pieces on a random lattice, a tenth of the bonds open), the
  // complete model's section with a lithostatic start under an overburden (the top face's
  // pressure and the prestress's out-of-plane term), and its 3-D block.
  const Scene stressed = read_problem_file(
      std::string(LATFRAC_PROBLEMS_DIR) + "/graben-complete-2d.toml",
      {"lattice.spacing=2000", "gravity.initial_stress=\"lithostatic\"", "gravity.overburden=2e7"});
  const Sample s = sample();
  Model complete = build_model(stressed);
  Vector u(complete.dofs().dof_count());
  for (Eigen::Index k = 0; k < u.size(); ++k) u[k] = 1e-3 * std::sin(static_cast<double>(k + 1));
  // And the complete model's 3-D block (a random lattice with face pieces on every face).
  const Scene block = read_problem_file(
      std::string(LATFRAC_PROBLEMS_DIR) + "/graben-complete-3d.toml", {"output.snapshots=[]"});
  Model complete_3d = build_model(block);
  Vector u3(complete_3d.dofs().dof_count());
  for (Eigen::Index k = 0; k < u3.size(); ++k) u3[k] = 1e-3 * std::cos(static_cast<double>(k + 1));
  for (const auto& [model, field] : {std::pair<const Model*, const Vector*>{&s.model, &s.u},
                                     {&complete, &u},
                                     {&complete_3d, &u3}}) {
    REQUIRE(!model->lattice.face_pieces.empty());
    // Every 37th node and every face node, listed twice and out of order.
    std::vector<std::int64_t> nodes;
    for (std::int64_t n = model->lattice.node_count() - 1; n >= 0; n -= 37) nodes.push_back(n);
    for (const FacePiece& piece : model->lattice.face_pieces) nodes.push_back(piece.node);
    nodes.push_back(nodes.front());
    for (int threads : {1, 3}) {
      const ThreadCount count(threads);
      const std::vector<double> all = node_stresses(*model, *field);
      const std::vector<double> some = node_stresses_at(*model, *field, nodes);
      REQUIRE(some.size() == all.size());
      std::vector<bool> listed(model->lattice.node_count(), false);
      for (const std::int64_t n : nodes) listed[n] = true;
      for (std::int64_t n = 0; n < model->lattice.node_count(); ++n)
        for (int k = 0; k < 6; ++k) {
          if (listed[n]) {
            REQUIRE(some[6 * n + k] == all[6 * n + k]);
          } else {
            REQUIRE(std::isnan(some[6 * n + k]));
          }
        }
    }
  }
}

TEST_CASE("an event-driven run breaks the same bonds at the same lambdas on 1 and 2 threads",
          "[threads][event]") {
  // The complete model's scene, short: contact friction, pair switches, cascades, and
  // every threaded sweep on two threads (12460 bonds, 4232 nodes).
  const Scene scene = read_problem_file(
      std::string(LATFRAC_PROBLEMS_DIR) + "/graben-complete-2d.toml",
      {"lattice.spacing=707.1", "loading.total=0.0004", "output.snapshots=[]"});
  RunResult result[2];
  for (int k = 0; k < 2; ++k) {
    const ThreadCount count(k + 1);
    RunOptions options;
    options.progress = false;
    result[k] = run_scene(scene, options);
  }
  REQUIRE(result[0].events.size() > 50);
  REQUIRE(result[1].events.size() == result[0].events.size());
  for (std::size_t e = 0; e < result[0].events.size(); ++e) {
    CHECK(result[1].events[e].bond == result[0].events[e].bond);
    CHECK(result[1].events[e].lambda == result[0].events[e].lambda);
    CHECK(result[1].events[e].failure_index == result[0].events[e].failure_index);
  }
}
