// What friction costs: the paper's Fig. 6 scene run event-driven with contact, frictionless
// (mu = 0, as shipped) and with Coulomb friction mu = 0.6, to the same lambda. With
// friction the scene breaks through most of its bonds, so the runs stop early (the
// argument); the cost is compared per break as well as per run. Each run is repeated and
// the fastest kept. Prints a table with the solver's counters.
//
//   build/bench/bench_friction                # from the source directory; to lambda 0.002
//   build/bench/bench_friction 0.004 2        # to lambda 0.004, 2 repeats

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "latfrac/io/problem_file.h"
#include "latfrac/scene/run.h"

using namespace latfrac;

int main(int argc, char** argv) {
  const std::string total = argc > 1 ? argv[1] : "0.002";
  const int repeats = argc > 2 ? std::stoi(argv[2]) : 1;
  const std::string fig6 = "problems/fig6-elliptic-graben-2d.toml";
  std::printf("Fig. 6 (%s), event-driven with contact, to lambda %s; fastest of %d\n\n",
              fig6.c_str(), total.c_str(), repeats);
  std::printf("| mu | breaks | wall s | ms per break | solves | factorizations | factor updates "
              "| contact slip m | friction work J/m |\n|---|---|---|---|---|---|---|---|---|\n");
  for (const char* mu : {"0", "0.6"}) {
    double best = 0;
    RunResult kept;
    for (int r = 0; r < repeats; ++r) {
      Scene scene = read_problem_file(
          fig6, {"stepping.method=\"event\"", std::string("contact.friction=") + mu,
                 "loading.total=" + total, "output.snapshots=[]"});
      const auto start = std::chrono::steady_clock::now();
      RunResult result = run_scene(scene, {});
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (r == 0 || seconds < best) {
        best = seconds;
        kept = std::move(result);
      }
    }
    const RunSummary& s = kept.summary;
    std::printf("| %s | %lld | %.2f | %.2f | %lld | %lld | %lld | %.4g | %.4g |\n", mu,
                static_cast<long long>(s.breaks), best,
                1e3 * best / static_cast<double>(std::max<std::int64_t>(s.breaks, 1)),
                static_cast<long long>(s.solves), static_cast<long long>(s.factorizations),
                static_cast<long long>(s.factor_updates), s.contact_slip, s.friction_work);
  }
  return 0;
}
