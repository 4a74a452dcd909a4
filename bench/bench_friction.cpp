// What friction costs: the paper's Fig. 6 scene run event-driven with contact, frictionless
// (mu = 0, as shipped) and with Coulomb friction mu = 0.6, to the same lambda. With
// friction the scene breaks through most of its bonds, so the runs stop early (the
// argument); the cost is compared per break as well as per run. Each run is repeated and
// the fastest kept. Prints a table with the solver's counters.
//
// With "3d" first: friction in 3-D on the paper's 3-D reference block (its pre-cut, with
// contact), event-driven: frictionless against mu = 0.6 with the polyhedral cone of 4, 8
// and 16 facets (docs/model.md, friction in 3-D). Then what the CVODE route would start
// from: the same block without contact, its affine event path against the integrated
// (CVODE + KINSOL) path that a circular cone would need, which here finds the same breaks.
//
//   build/bench/bench_friction                # from the source directory; to lambda 0.002
//   build/bench/bench_friction 0.004 2        # to lambda 0.004, 2 repeats
//   build/bench/bench_friction 3d 0.004 3000  # 3-D, to lambda 0.004, spacing 3000 m

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "latfrac/io/problem_file.h"
#include "latfrac/scene/model_builder.h"
#include "latfrac/scene/run.h"
#include "scenes.h"  // tests/: run_model, which can follow the integrated path

using namespace latfrac;

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void three_d(const std::string& total, const std::string& spacing) {
  const std::string block = "problems/reference-3d.toml";
  const std::vector<std::string> common = {"stepping.method=\"event\"", "loading.total=" + total,
                                           "lattice.spacing=" + spacing, "output.snapshots=[]"};
  std::printf("3-D reference block (%s) at %s m, event-driven with contact, to lambda %s\n\n",
              block.c_str(), spacing.c_str(), total.c_str());
  std::printf("| mu | facets | breaks | wall s | ms per break | solves | factorizations | "
              "contact slip m | friction work J |\n|---|---|---|---|---|---|---|---|---|\n");
  for (const int facets : {0, 4, 8, 16}) {
    std::vector<std::string> set = common;
    if (facets > 0) {
      set.push_back("contact.friction=0.6");
      set.push_back("contact.friction_facets=" + std::to_string(facets));
    }
    const Scene scene = read_problem_file(block, set);
    const auto start = std::chrono::steady_clock::now();
    const RunResult result = run_scene(scene, {});
    const double wall = seconds_since(start);
    const RunSummary& s = result.summary;
    std::printf("| %s | %s | %lld | %.2f | %.2f | %lld | %lld | %.4g | %.4g |\n",
                facets ? "0.6" : "0", facets ? std::to_string(facets).c_str() : "-",
                static_cast<long long>(s.breaks), wall,
                1e3 * wall / static_cast<double>(std::max<std::int64_t>(s.breaks, 1)),
                static_cast<long long>(s.solves), static_cast<long long>(s.factorizations),
                s.contact_slip, s.friction_work);
  }

  std::printf("\nThe same block without contact: affine events against the CVODE route\n\n");
  std::printf("| path | breaks | wall s | ms per break | same breaks |\n|---|---|---|---|---|\n");
  std::vector<std::int64_t> first;
  for (const bool integrated : {false, true}) {
    std::vector<std::string> set = common;
    set.push_back("contact.enabled=false");
    const Scene scene = read_problem_file(block, set);
    Model model = build_model(scene);
    const auto start = std::chrono::steady_clock::now();
    const RunResult result = testing::run_model(model, scene, integrated);
    const double wall = seconds_since(start);
    std::vector<std::int64_t> bonds;
    for (const auto& e : result.events)
      if (e.mode != BreakMode::precut) bonds.push_back(e.bond);
    if (!integrated) first = bonds;
    const auto breaks = static_cast<long long>(bonds.size());
    std::printf("| %s | %lld | %.2f | %.2f | %s |\n", integrated ? "CVODE" : "affine", breaks,
                wall, 1e3 * wall / static_cast<double>(std::max(breaks, 1LL)),
                bonds == first ? "yes" : "no");
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && std::string(argv[1]) == "3d") {
    three_d(argc > 2 ? argv[2] : "0.004", argc > 3 ? argv[3] : "3000");
    return 0;
  }
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
