// Where a run's time goes (base/phase_times.h): the clock's accounting on a clock the
// test sets by hand, and a run's split, which adds up to its wall time.
#include "latfrac/base/phase_times.h"

#include <catch2/catch.hpp>
#include <numeric>

#include "latfrac/io/problem_file.h"
#include "latfrac/io/result_file.h"
#include "latfrac/scene/run.h"
#include "sample_result.h"

using namespace latfrac;

namespace {

double part(const std::array<double, phase_count>& seconds, Phase phase) {
  return seconds[static_cast<int>(phase)];
}

}  // namespace

TEST_CASE("the phase clock gives each second to the innermost open phase", "[phases]") {
  double t = 0;
  PhaseClock clock([&] { return t; });
  t = 1;  // nothing open: the rest
  clock.enter(Phase::contacts);
  t = 3;
  clock.enter(Phase::solve);  // a solve inside a contact switch
  t = 7;
  clock.enter(Phase::refactorize);  // a refactorization inside the solve
  t = 8;
  clock.leave();
  t = 10;
  clock.leave();
  t = 10.5;
  clock.leave();
  t = 12;
  auto seconds = clock.seconds();
  CHECK(part(seconds, Phase::other) == 2.5);      // 0-1 and 10.5-12
  CHECK(part(seconds, Phase::contacts) == 2.5);   // 1-3 and 10-10.5
  CHECK(part(seconds, Phase::solve) == 6);        // 3-7 and 8-10
  CHECK(part(seconds, Phase::refactorize) == 1);  // 7-8
  CHECK(std::accumulate(seconds.begin(), seconds.end(), 0.0) == 12);
  // An open phase counts up to now; a leave() with nothing open changes nothing.
  clock.enter(Phase::output);
  t = 13;
  CHECK(part(clock.seconds(), Phase::output) == 1);
  clock.leave();
  clock.leave();
  t = 14;
  CHECK(part(clock.seconds(), Phase::other) == 3.5);
  clock.reset();
  t = 15;
  seconds = clock.seconds();
  CHECK(part(seconds, Phase::other) == 1);
  CHECK(std::accumulate(seconds.begin(), seconds.end(), 0.0) == 1);
}

TEST_CASE("a run's time by part adds up to its wall time, and is not stored in the file",
          "[phases]") {
  // The complete model, short: solves, factor updates, node stresses, the criterion and
  // the contacts' switches all take part.
  const Scene scene = read_problem_file(
      std::string(LATFRAC_PROBLEMS_DIR) + "/graben-complete-2d.toml",
      {"lattice.spacing=2000", "loading.total=0.004", "output.snapshots=[0.004]"});
  RunOptions options;
  options.progress = false;
  const RunResult result = run_scene(scene, options);
  const auto& seconds = result.summary.phase_seconds;
  const double sum = std::accumulate(seconds.begin(), seconds.end(), 0.0);
  for (double s : seconds) CHECK(s >= 0);
  // The split starts just after the wall clock and ends just before it.
  CHECK(sum <= result.summary.wall_seconds);
  CHECK(sum >= 0.9 * result.summary.wall_seconds);
  REQUIRE(result.summary.solves > 0);
  REQUIRE(result.summary.factor_updates > 0);
  for (Phase phase : {Phase::setup, Phase::solve, Phase::factor_update, Phase::node_stress,
                      Phase::criterion, Phase::residual, Phase::contacts, Phase::output})
    CHECK(part(seconds, phase) > 0);
  CHECK(summary_text(result).find("time by part (this process, s): setup ") != std::string::npos);
  // Read back from a file, the run has no split, and its summary says none.
  testing::ScratchDirectory scratch;
  const std::string path = scratch.file("split.h5");
  write_result_file(path, result);
  const RunResult back = read_result_file(path);
  CHECK(std::accumulate(back.summary.phase_seconds.begin(), back.summary.phase_seconds.end(),
                        0.0) == 0);
  CHECK(summary_text(back).find("time by part") == std::string::npos);
}
