// What the path screen saves (fracture/path_screen.h): the complete 2-D scene, event-driven,
// with every crossing search in full and with the screen, alternated, one run at a time;
// the events of the two compared bond for bond and lambda for lambda. Prints a table.
//
//   build/bench/bench_screen                   # from the source directory; 1000 m, 2 pairs
//   build/bench/bench_screen 707.1 3           # spacing (m), pairs
//   build/bench/bench_screen 1000 2 3d         # the 3-D scene, to lambda 0.0006

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "latfrac/base/threads.h"
#include "latfrac/io/problem_file.h"
#include "scenes.h"

using namespace latfrac;

int main(int argc, char** argv) {
  const std::string spacing = argc > 1 ? argv[1] : "1000";
  const int pairs = argc > 2 ? std::max(1, std::atoi(argv[2])) : 2;
  const bool three_d = argc > 3 && std::string(argv[3]) == "3d";
  std::vector<std::string> sets = {"lattice.spacing=" + spacing, "output.snapshots=[]"};
  if (three_d) sets.push_back("loading.total=0.0006");
  const std::string file =
      std::string("problems/graben-complete-") + (three_d ? "3d" : "2d") + ".toml";
  const Scene scene = read_problem_file(file, sets);
  std::printf("%s at %s m, event-driven; threads: %d; %d pairs, full search first\n\n",
              file.c_str(), spacing.c_str(), threads::count(), pairs);
  std::printf(
      "| pair | breaks | searches screened | searched in full | full search s | screened s | same "
      "events |\n"
      "|---|---|---|---|---|---|---|\n");
  for (int pair = 1; pair <= pairs; ++pair) {
    RunResult result[2];
    double seconds[2];
    std::int64_t searches[2] = {0, 0};
    for (int with = 0; with < 2; ++with) {
      Model model = build_model(scene);
      const auto start = std::chrono::steady_clock::now();
      result[with] = testing::run_model(model, scene, false, with == 1, &searches);
      seconds[with] =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    bool same = result[0].events.size() == result[1].events.size();
    for (std::size_t k = 0; same && k < result[0].events.size(); ++k)
      same = result[0].events[k].bond == result[1].events[k].bond &&
             result[0].events[k].lambda == result[1].events[k].lambda;
    std::printf("| %d | %zu | %lld | %lld | %.2f | %.2f | %s |\n", pair, result[1].events.size(),
                static_cast<long long>(searches[0]), static_cast<long long>(searches[1]),
                seconds[0], seconds[1], same ? "yes" : "NO");
    std::fflush(stdout);
  }
  return 0;
}
