// Benchmark of the elastic equilibrium: assembly, CHOLMOD analysis, factorization, a
// two-RHS solve, and KINSOL's Newton solve against the bare CHOLMOD work. Prints a table.
//
//   build/bench/bench_equilibrium            # the three standard cases
//   build/bench/bench_equilibrium 2 100000   # one case: dim and approximate node count
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "bench_cases.h"
#include "latfrac/solvers/cholesky.h"
#include "latfrac/solvers/equilibrium.h"
#include "latfrac/scene/model_builder.h"

using namespace latfrac;

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The paper's material in a box of about `nodes` nodes (2-D 2:1, 3-D 3:1:1.5), a = 100 m.
Scene bench_scene(int dim, long nodes) {
  Scene scene;
  scene.name = "bench";
  scene.lattice.dim = dim;
  scene.lattice.spacing = 100.0;
  scene.material = {2600.0, 100e9, 0.2};
  scene.gravity = Gravity{9.81};
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

void run_case(int dim, long nodes) {
  const Scene scene = bench_scene(dim, nodes);
  auto start = std::chrono::steady_clock::now();
  Model model = build_model(scene);
  const double build = seconds_since(start);
  const std::int64_t n = model.dofs().free_count;

  // Bare CHOLMOD: assemble, analyze, factorize, one two-column solve. Each measurement
  // is the faster of two repetitions, so that neither side pays for cold caches alone.
  double assemble = 1e300, analyze = 1e300, factorize = 1e300, solve = 1e300, kinsol = 1e300;
  std::int64_t factor_entries = 0;
  EquilibriumReport report;
  for (int repetition = 0; repetition < 2; ++repetition) {
    // The bare objects are freed before KINSOL runs, so that both sides allocate into the
    // same warm memory; otherwise KINSOL alone pays for first-touch page faults.
    {
      start = std::chrono::steady_clock::now();
      StiffnessMatrix stiffness(model);
      stiffness.assemble(model, Vector::Zero(model.dofs().dof_count()));
      assemble = std::min(assemble, seconds_since(start));
      CholeskyFactor factor(scene.solver.ordering);
      start = std::chrono::steady_clock::now();
      factor.analyze(stiffness);
      analyze = std::min(analyze, seconds_since(start));
      start = std::chrono::steady_clock::now();
      factor.factorize(stiffness);
      factorize = std::min(factorize, seconds_since(start));
      Eigen::MatrixXd rhs(n, 2);
      rhs.col(0) = -model.residual(Vector::Zero(n), 0.0);
      rhs.col(1) = -model.residual(Vector::Zero(n), 1.0) - rhs.col(0);
      start = std::chrono::steady_clock::now();
      factor.solve(rhs.data(), n, 2);
      solve = std::min(solve, seconds_since(start));
      factor_entries = factor.factor_nonzeros();
    }

    // KINSOL from a zero guess at lambda = 0.01: residuals, tangent, analysis,
    // factorization, solve, all through the SUNDIALS interfaces.
    EquilibriumSolver solver(model, scene.solver);
    Vector u = Vector::Zero(n);
    start = std::chrono::steady_clock::now();
    report = solver.solve(0.01, u);
    kinsol = std::min(kinsol, seconds_since(start));
  }
  const double bare = assemble + analyze + factorize + solve;

  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  std::printf(
      "| %d-D | %8ld | %8ld | %6.2f | %8.3f | %7.3f | %9.3f | %7.3f | %10.2f | %7.0f | %6.3f | "
      "%2ld | %+7.1f %% |\n",
      dim, static_cast<long>(model.lattice.node_count()), static_cast<long>(n), build, assemble,
      analyze, factorize, solve, factor_entries / 1e6, usage.ru_maxrss / 1024.0, kinsol,
      report.newton_iterations, 100 * (kinsol - bare) / bare);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  std::printf(
      "| dim | nodes | free DOFs | build s | assemble s | analyze s | factorize s | solve(2) s "
      "| nnz(L) 1e6 | peak MB | KINSOL s | Newton its | KINSOL vs bare |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  std::fflush(stdout);
  std::vector<std::pair<int, long>> cases = {{2, 100000}, {3, 10000}, {3, 50000}};
  if (argc == 3) cases = {{std::stoi(argv[1]), std::stol(argv[2])}};
  bench::run_each_in_child(cases, [&](int dim, long nodes) { run_case(dim, nodes); });
  std::printf(
      "\nKINSOL vs bare: KINSOL's Newton solve against assemble + analyze + factorize + solve.\n");
  return 0;
}
