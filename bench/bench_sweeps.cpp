// What one sweep over every bond costs: the node stresses along a path (two fields, as the
// event search reads them) and the internal forces (as a residual check sums them), on the
// complete 2-D scene's random lattice at three spacings. Each sweep is repeated and the
// fastest of three rounds kept. Prints a table.
//
//   build/bench/bench_sweeps              # from the source directory; 200 sweeps a round
//   build/bench/bench_sweeps 500          # 500 sweeps a round
//   LATFRAC_THREADS=1 build/bench/bench_sweeps

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <string>

#include "latfrac/base/threads.h"
#include "latfrac/io/problem_file.h"
#include "latfrac/mechanics/node_stress.h"
#include "latfrac/scene/model_builder.h"

using namespace latfrac;

namespace {

// The fastest of three rounds of `reps` calls, in ms per call.
template <class Sweep>
double fastest_ms(int reps, const Sweep& sweep) {
  double best = 1e300;
  for (int round = 0; round < 3; ++round) {
    const auto start = std::chrono::steady_clock::now();
    for (int r = 0; r < reps; ++r) sweep(r);
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    best = std::min(best, 1e3 * s / reps);
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  const int reps = argc > 1 ? std::max(1, std::atoi(argv[1])) : 200;
  std::printf(
      "problems/graben-complete-2d.toml, intact lattice, random displacements; "
      "threads: %d; fastest of 3 rounds of %d sweeps\n\n",
      threads::count(), reps);
  std::printf(
      "| spacing m | nodes | bonds | node_stress_path ms | internal_force ms |\n"
      "|---|---|---|---|---|\n");
  for (const char* spacing : {"1000", "707.1", "500"}) {
    const Scene scene =
        read_problem_file("problems/graben-complete-2d.toml",
                          {std::string("lattice.spacing=") + spacing, "output.snapshots=[]"});
    const Model model = build_model(scene);
    const auto dofs = model.dofs().dof_count();
    std::mt19937 random(1);
    std::uniform_real_distribution<double> uniform(-1, 1);
    Vector at_zero(dofs), per_unit(dofs);
    for (Eigen::Index i = 0; i < dofs; ++i) {
      at_zero[i] = uniform(random);
      per_unit[i] = uniform(random);
    }
    model.node_bonds();
    double checksum = 0;  // sums a value of each sweep's result, printed: keeps them computed
    const double stresses = fastest_ms(reps, [&](int r) {
      const NodeStressPath path = node_stress_path(model, at_zero, per_unit);
      checksum += path.at_zero[static_cast<std::size_t>(r) % path.at_zero.size()];
    });
    const double forces =
        fastest_ms(reps, [&](int r) { checksum += model.internal_force(at_zero)[r % dofs]; });
    std::printf("| %s | %lld | %lld | %.3f | %.3f |\n", spacing,
                static_cast<long long>(model.lattice.node_count()),
                static_cast<long long>(model.lattice.bond_count()), stresses, forces);
    std::fprintf(stderr, "spacing %s: checksum %.6g\n", spacing, checksum);
  }
}
