// Benchmark of the mechanism rule (docs/robustness.md, "Mechanisms"): what its checks cost
// against the factorization they follow, and a whole run. Prints a table.
//
//   build/bench/bench_mechanisms                                   # Fig. 6 as shipped
//   build/bench/bench_mechanisms problems/fig6-elliptic-graben-2d.toml lattice.spacing=250
//   build/bench/bench_mechanisms problems/fig6-elliptic-graben-2d.toml material.poisson=0.25
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "latfrac/io/problem_file.h"
#include "latfrac/scene/model_builder.h"
#include "latfrac/scene/run.h"
#include "latfrac/solvers/cholesky.h"

using namespace latfrac;

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The fastest of `repetitions` timings of `work`, in seconds.
template <typename Work>
double fastest(int repetitions, Work work) {
  double best = 1e300;
  for (int r = 0; r < repetitions; ++r) {
    const auto start = std::chrono::steady_clock::now();
    work();
    best = std::min(best, seconds_since(start));
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : "problems/fig6-elliptic-graben-2d.toml";
  std::vector<std::string> overrides(argv + std::min(argc, 2), argv + argc);
  const Scene scene = read_problem_file(path, overrides);
  Model model = build_model(scene);
  StiffnessMatrix stiffness(model);
  stiffness.assemble(model, model.full_displacement(Vector::Zero(model.dofs().free_count), 0.0));
  CholeskyFactor factor(scene.solver.ordering);
  factor.analyze(stiffness);

  // 1. A fresh factorization (with the scan it now makes) and the scan alone.
  const double factorize = fastest(5, [&] { factor.factorize(stiffness); });
  const double scan = fastest(5, [&] { factor.find_weakest_pivot(stiffness); });
  // 2. The motion at the weakest pivot: only when that pivot is below 1e-6 of its diagonal.
  const double mode = fastest(5, [&] { factor.null_mode(stiffness); });
  std::printf("%s (%s), %lld unknowns, weakest pivot %.2e of its diagonal\n", path.c_str(),
              scene.name.c_str(), static_cast<long long>(model.dofs().free_count),
              factor.weakest_pivot().ratio);
  std::printf("%-44s %12s\n", "step", "ms");
  std::printf("%-44s %12.3f\n", "fresh factorization (scan included)", 1e3 * factorize);
  std::printf("%-44s %12.3f\n", "  pivot scan", 1e3 * scan);
  std::printf("%-44s %12.3f\n", "null mode (pivot below 1e-6 only)", 1e3 * mode);

  // 3. The whole run: the checks' share from its counts.
  RunOptions options;
  options.progress = false;
  const RunResult result = run_scene(scene, options);
  const RunSummary& s = result.summary;
  const double share = s.factorizations * scan;
  std::printf("run: %.3f s, %lld breaks, %lld factorizations, %lld updates, %lld solves\n",
              s.wall_seconds, static_cast<long long>(s.breaks),
              static_cast<long long>(s.factorizations), static_cast<long long>(s.factor_updates),
              static_cast<long long>(s.solves));
  std::printf("pivot scans %.4f s (%.2f %% of the run): one per factorization\n", share,
              100 * share / s.wall_seconds);
  return 0;
}
