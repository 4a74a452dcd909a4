// Benchmark of one break in a cascade: factor downdate + re-solve at the cascade's lambda
// (one right-hand side, with its residual check) +
// criterion evaluation, against a full refactorization; and the criterion evaluation of
// every bond against one re-solve; and the time to build the lattice. Prints a table.
//
//   build/bench/bench_breaking              # 2-D 100k and 3-D 50k nodes, regular and random
//   build/bench/bench_breaking 3 10000      # one case: dim and approximate node count
//   build/bench/bench_breaking 2 100000 nesdis   # ... and the fill-reducing ordering
//   build/bench/bench_breaking 2 100000 metis random   # ... and the lattice kind only

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <string>

#include "bench_cases.h"
#include "latfrac/solvers/equilibrium.h"
#include "latfrac/criteria/failure_evaluator.h"
#include "latfrac/scene/model_builder.h"
#include "random_breaks.h"

using namespace latfrac;

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The paper's crust with the elliptic criterion, about `nodes` nodes, a = 100 m.
Scene bench_scene(int dim, long nodes, LatticeKind kind) {
  Scene scene;
  scene.name = "bench";
  scene.lattice.dim = dim;
  scene.lattice.kind = kind;
  scene.lattice.seed = 1;
  scene.lattice.spacing = 100.0;
  scene.material = {2600.0, 100e9, 0.2};
  scene.gravity = Gravity{9.81};
  Strength strength;
  strength.criterion = Criterion::elliptic;
  strength.sigma0 = 50e6;
  strength.friction_angle = 34.0;
  scene.strength = strength;
  const double a = scene.lattice.spacing;
  if (dim == 2) {
    const double height = std::sqrt(nodes * std::sqrt(3.0) / 2 / 2) * a;
    scene.lattice.size = {2 * height, 0, height};
  } else {
    const double unit = std::cbrt(nodes / std::sqrt(2.0) / 4.5) * a;
    scene.lattice.size = {3 * unit, unit, 1.5 * unit};
  }
  return scene;
}

void run_case(int dim, long nodes, Ordering ordering, LatticeKind kind) {
  Scene scene = bench_scene(dim, nodes, kind);
  scene.solver.ordering = ordering;
  auto start = Clock::now();
  const std::clock_t cpu_start = std::clock();
  build_lattice(scene.lattice);
  const double construction = seconds_since(start);  // the lattice alone, as build_model does
  // Its processor time too: on a shared machine the wall time can be several times longer.
  const double construction_cpu = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  Model model = build_model(scene);
  EquilibriumSolver solver(model, scene.solver);
  const FailureEvaluator evaluator(*scene.strength, model);
  const double lambda = 1e-4;

  AffinePath path = solver.affine_path();  // analysis + supernodal factorization
  start = Clock::now();
  solver.discard_factor();
  path = solver.affine_path();
  const double refactorization = seconds_since(start);  // assemble + factorize + 2-RHS solve

  start = Clock::now();
  const int evaluations = 5;
  CriticalBond critical;
  for (int k = 0; k < evaluations; ++k)
    critical = evaluator.most_critical(model, model.full_displacement(path.at(lambda), lambda));
  const double criterion = seconds_since(start) / evaluations;

  // Breaks of random bonds that leave the body supported: downdate, re-solve and check,
  // evaluate the criterion. The first update converts the factor to simplicial LDL'.
  const int breaks = 10;
  double update = 0, resolve = 0, evaluate = 0;
  int done = -1;  // the first break pays the conversion to LDL'; reported apart
  testing::for_random_supported_breaks(model, breaks + 1, 7, [&](std::int64_t bond) {
    auto t0 = Clock::now();
    solver.set_pair_state(bond, PairState::open);
    auto t1 = Clock::now();
    const Vector u = solver.checked_solve(lambda);
    auto t2 = Clock::now();
    critical = evaluator.most_critical(model, model.full_displacement(u, lambda));
    auto t3 = Clock::now();
    if (done++ < 0) return;
    update += std::chrono::duration<double>(t1 - t0).count();
    resolve += std::chrono::duration<double>(t2 - t1).count();
    evaluate += std::chrono::duration<double>(t3 - t2).count();
  });
  update /= breaks;
  resolve /= breaks;
  evaluate /= breaks;
  const double per_break = update + resolve + evaluate;
  std::printf(
      "| %d-D | %-10s | %8ld | %8ld | %7.3f | %7.3f | %9.3f | %9.4f | %9.4f | %9.4f | %9.4f | %6.1f %% | "
      "%9.4f | %6.1f %% |\n",
      dim, lattice_kind_name(dim, kind), static_cast<long>(model.lattice.node_count()),
      static_cast<long>(model.lattice.bond_count()), construction, construction_cpu, refactorization, update, resolve,
      evaluate, per_break, 100 * per_break / refactorization, criterion, 100 * criterion / resolve);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  std::printf(
      "| dim | lattice | nodes | bonds | build s | build cpu s | refactorize s | update s | re-solve + check s "
      "| criterion s | per break s | break / refactorize | all-bond criterion s | criterion / "
      "re-solve |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  std::fflush(stdout);
  std::vector<std::pair<int, long>> cases = {{2, 100000}, {3, 50000}};
  if (argc >= 3) cases = {{std::stoi(argv[1]), std::stol(argv[2])}};
  const std::string name = argc >= 4 ? argv[3] : "metis";
  const Ordering ordering = name == "nesdis" ? Ordering::nesdis
                            : name == "amd"  ? Ordering::amd
                                             : Ordering::metis;
  const std::string only = argc >= 5 ? argv[4] : "";
  std::vector<LatticeKind> kinds;
  if (only != "random") kinds.push_back(LatticeKind::regular);
  if (only != "regular") kinds.push_back(LatticeKind::random);
  for (const auto& one_case : cases) {
    for (const LatticeKind kind : kinds) {
      bench::run_each_in_child({one_case}, [&](int dim, long nodes) {
        run_case(dim, nodes, ordering, kind);
      });
    }
  }
  std::printf(
      "\nper break = factor downdate + re-solve at lambda with its residual check "
      "+ criterion of every bond; refactorize = assembly + numeric factorization + solve;\n"
      "build = the lattice alone (positions, bonds, faces; for a random lattice the sampling,\n"
      "the Delaunay triangulation and the Voronoi facets).\n");
  return 0;
}
