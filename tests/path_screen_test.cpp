// The path screen (fracture/path_screen.h): its bound on the node stresses, the node
// stresses it sums at a few nodes, and the events of runs with and without it.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "latfrac/io/problem_file.h"
#include "latfrac/mechanics/node_stress.h"
#include "scenes.h"

using namespace latfrac;
using namespace latfrac::testing;

namespace {

Scene complete_scene(int dim, double spacing, std::vector<std::string> more = {}) {
  more.push_back("lattice.spacing=" + std::to_string(spacing));
  return read_problem_file(
      std::string(LATFRAC_PROBLEMS_DIR) + "/graben-complete-" + std::to_string(dim) + "d.toml",
      more);
}

Vector random_field(std::int64_t size, double scale, std::mt19937& random) {
  std::uniform_real_distribution<double> uniform(-scale, scale);
  Vector u(size);
  for (std::int64_t k = 0; k < size; ++k) u[k] = uniform(random);
  return u;
}

// The Frobenius norm of node n's stress (in 2-D its x-z part: xx, zz and xz).
double stress_norm(const std::vector<double>& v, std::int64_t n, int dim) {
  const double* s = &v[6 * n];
  if (dim == 2) return std::sqrt(s[0] * s[0] + s[2] * s[2] + 2 * s[4] * s[4]);
  return std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2] +
                   2 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
}

}  // namespace

TEST_CASE(
    "Node stress bounds: a node's stress moves by at most its bound times the largest "
    "displacement change",
    "[screen][stress]") {
  // The bound is a sum of sizes (triangle inequality), checked here against the virial
  // itself on random changes: never exceeded, and not vacuous (some node comes within a
  // factor 20 of it). A change concentrated on one node's neighbours comes closest.
  const int dim = GENERATE(2, 3);
  const bool random_lattice = GENERATE(true, false);
  Scene scene = random_lattice
                    ? complete_scene(dim, dim == 2 ? 2000.0 : 4000.0)
                    : box_scene(dim, dim == 2 ? 2000.0 : 5000.0, {30e3, 20e3, 15e3}, true);
  const Model model = build_model(scene);
  const std::vector<double> bound = node_stress_bounds(model);
  std::mt19937 random(77 + dim);
  double closest = 0;
  for (int trial = 0; trial < 4; ++trial) {
    Vector change = random_field(model.dofs().dof_count(), 0.3, random);
    if (trial % 2 == 1) {
      // Alternating signs node by node: neighbours move apart, as far as the field allows.
      for (std::int64_t k = 0; k < change.size(); ++k)
        change[k] = ((k / dim) % 2 == 0 ? 0.3 : -0.3) * (k % dim == 0 ? 1 : -1);
    }
    const double largest = change.cwiseAbs().maxCoeff();
    const std::vector<double> moved = node_stress_rates(model, change);
    for (std::int64_t n = 0; n < model.lattice.node_count(); ++n) {
      const double size = stress_norm(moved, n, dim);
      INFO("node " << n << ": " << size << " Pa against the bound " << bound[n] * largest);
      REQUIRE(size <= bound[n] * largest * (1 + 1e-12));
      closest = std::max(closest, size / (bound[n] * largest));
    }
  }
  CHECK(closest > 0.05);
}

TEST_CASE("node_stress_path_at gives the sweep's node stresses bit for bit", "[screen][stress]") {
  const int dim = GENERATE(2, 3);
  Scene scene = complete_scene(dim, dim == 2 ? 2000.0 : 4000.0);
  const Model model = build_model(scene);
  std::mt19937 random(5);
  const Vector at_zero = random_field(model.dofs().dof_count(), 2.0, random);
  const Vector per_unit = random_field(model.dofs().dof_count(), 3e4, random);
  const NodeStressPath all = node_stress_path(model, at_zero, per_unit);
  // Face nodes (with supports) and inner ones: every fifth node.
  std::vector<std::int64_t> nodes;
  for (std::int64_t n = 0; n < model.lattice.node_count(); n += 5) nodes.push_back(n);
  const NodeStressPath some = node_stress_path_at(model, at_zero, per_unit, nodes);
  for (const std::int64_t n : nodes) {
    for (int k = 0; k < 6; ++k) {
      INFO("node " << n << ", component " << k);
      REQUIRE(some.at_zero[6 * n + k] == all.at_zero[6 * n + k]);
      REQUIRE(some.per_unit[6 * n + k] == all.per_unit[6 * n + k]);
    }
  }
  CHECK(std::isnan(some.at_zero[6 * 1]));
}

TEST_CASE("The screened crossing search finds the full search's events",
          "[screen][random][friction]") {
  // The complete model, where contact switches follow each other within a hair of lambda:
  // with the screen most searches skip the sweep, and every event is the same, bit for
  // bit (the searched bonds' crossings are computed from the same numbers).
  const int dim = GENERATE(2, 3);
  const Scene scene =
      dim == 2 ? complete_scene(2, 1414.0, {"output.snapshots=[0.04]"})
               : complete_scene(3, 4000.0, {"loading.total=0.002", "output.snapshots=[0.002]"});
  std::int64_t screened[2] = {0, 0}, unscreened[2] = {0, 0};
  Model plain_model = build_model(scene);
  const RunResult plain = run_model(plain_model, scene, false, false, &unscreened);
  Model screened_model = build_model(scene);
  const RunResult with_screen = run_model(screened_model, scene, false, true, &screened);
  CHECK(unscreened[0] + unscreened[1] == 0);
  CHECK(screened[0] > 0);  // the screened route was taken
  CHECK(screened[1] > 0);
  REQUIRE(plain.events.size() > 100);
  REQUIRE(with_screen.events.size() == plain.events.size());
  for (std::size_t k = 0; k < plain.events.size(); ++k) {
    INFO("event " << k);
    REQUIRE(with_screen.events[k].bond == plain.events[k].bond);
    REQUIRE(with_screen.events[k].mode == plain.events[k].mode);
    REQUIRE(with_screen.events[k].lambda == plain.events[k].lambda);
  }
  CHECK(with_screen.summary.solves == plain.summary.solves);
}
