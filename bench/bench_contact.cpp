// What contact costs: the paper's Fig. 6 scene run event-driven against fixed-step at
// ds = 1e-3 (both with contact, as shipped), and the 3-D reference run event-driven with
// and without contact, per break. Each run is repeated and the fastest kept (the machine's
// other work only ever adds time). Prints a table with the solver's counters.
//
//   build/bench/bench_contact                 # from the source directory; 3 repeats
//   build/bench/bench_contact 5 2000          # 5 repeats, the 3-D block at 2000 m

#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "latfrac/io/problem_file.h"
#include "latfrac/scene/run.h"

using namespace latfrac;

namespace {

using Clock = std::chrono::steady_clock;

struct Timed {
  double seconds = 0;
  RunSummary summary;
  std::size_t breaks = 0;
};

Timed fastest(const std::string& file, const std::vector<std::string>& overrides, int repeats) {
  Timed best;
  for (int r = 0; r < repeats; ++r) {
    Scene scene = read_problem_file(file, overrides);
    scene.output.snapshots.clear();
    const auto start = Clock::now();
    const RunResult result = run_scene(scene, {});
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    if (r == 0 || seconds < best.seconds) {
      best.seconds = seconds;
      best.summary = result.summary;
      best.breaks = 0;
      for (const BreakEvent& e : result.events) best.breaks += e.mode != BreakMode::precut;
    }
  }
  return best;
}

void row(const char* name, const Timed& t) {
  const RunSummary& s = t.summary;
  std::printf("| %s | %zu | %.3f | %.3f | %lld | %lld | %lld |\n", name, t.breaks, t.seconds,
              1e3 * t.seconds / static_cast<double>(std::max<std::size_t>(t.breaks, 1)),
              static_cast<long long>(s.solves), static_cast<long long>(s.factor_updates),
              static_cast<long long>(s.factorizations));
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::stoi(argv[1]) : 3;
  const std::string spacing = argc > 2 ? argv[2] : "3000";
  const std::string fig6 = "problems/fig6-elliptic-graben-2d.toml";
  const std::string ref = "problems/reference-3d.toml";
  std::printf("fastest of %d runs each; wall seconds of run_scene (no result file)\n\n", repeats);
  std::printf("| run | breaks | wall s | ms per break | solves | factor updates | factorizations |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|\n");
  const Timed event = fastest(fig6, {"stepping.method=event"}, repeats);
  const Timed fixed = fastest(fig6, {"stepping.method=fixed", "stepping.increment=1e-3"}, repeats);
  row("Fig. 6, contact, event-driven", event);
  row("Fig. 6, contact, fixed ds = 1e-3", fixed);
  const std::vector<std::string> three_d{"stepping.method=event", "lattice.spacing=" + spacing};
  std::vector<std::string> without = three_d;
  without.push_back("contact.enabled=false");
  const Timed with_contact = fastest(ref, three_d, repeats);
  const Timed no_contact = fastest(ref, without, repeats);
  const std::string with_name = "3-D reference " + spacing + " m, contact, event";
  const std::string without_name = "3-D reference " + spacing + " m, no contact, event";
  row(with_name.c_str(), with_contact);
  row(without_name.c_str(), no_contact);
  const auto per_break = [](const Timed& t) {
    return t.seconds / static_cast<double>(std::max<std::size_t>(t.breaks, 1));
  };
  std::printf("\nFig. 6: event-driven / fixed ds = 1e-3 = %.2f (target <= 1.5)\n",
              event.seconds / fixed.seconds);
  std::printf("3-D: per break with contact / without = %.2f (target <= 2)\n",
              per_break(with_contact) / per_break(no_contact));
  return 0;
}
