// Tests of checkpoints and resume: a run stopped anywhere between events (or between the
// groups of a cascade) and resumed from its result file gives the uninterrupted run's
// events, bit for bit (the spec asks for lambdas to 1e-12 relative).
#include <hdf5.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <functional>
#include <random>
#include <vector>

#include "latfrac/base/error.h"
#include "latfrac/io/problem_file.h"
#include "latfrac/io/result_file.h"
#include "latfrac/io/result_writer.h"
#include "latfrac/scene/run.h"
#include "sample_result.h"

namespace latfrac {
namespace {

using testing::ScratchDirectory;

Scene shipped(const std::string& problem, std::vector<std::string> overrides) {
  return read_problem_file(std::string(LATFRAC_PROBLEMS_DIR) + "/" + problem, overrides);
}

// Saves to `path` and stops at its `stop_at`-th chance (each check between events or
// between groups is one); never stops when stop_at is 0, and then counts the chances.
class StopAt final : public RunControl {
 public:
  StopAt(std::string path, long stop_at) : path_(std::move(path)), stop_at_(stop_at) {}
  bool stop_requested() const override { return ++chances_ == stop_at_; }
  bool checkpoint_due() override { return false; }
  void save(RunResult& result, RunCheckpoint& checkpoint) override {
    write_result_file(path_, result, &checkpoint);
  }
  long chances() const { return chances_; }

 private:
  std::string path_;
  long stop_at_;
  mutable long chances_ = 0;
};

RunResult run_with(const Scene& scene, RunControl* control, const ResumePoint* resume) {
  RunOptions options;
  options.progress = false;
  options.control = control;
  options.resume = resume;
  return run_scene(scene, options);
}

// Runs the scene, stopping at each of the given chances in turn (counted afresh in each
// resumed part) and resuming from the file, until it completes.
RunResult stopped_and_resumed(const Scene& scene, const std::vector<long>& stops,
                              const std::string& path) {
  ResumePoint point;
  bool resuming = false;
  for (long stop : stops) {
    StopAt control(path, stop);
    RunResult result = run_with(scene, &control, resuming ? &point : nullptr);
    if (result.summary.complete) return result;
    const RunResult on_disk = read_result_file(path);
    CHECK_FALSE(on_disk.summary.complete);
    point.result = on_disk;
    point.checkpoint = read_checkpoint(path);
    resuming = true;
  }
  return run_with(scene, nullptr, resuming ? &point : nullptr);
}

void require_same_events(const RunResult& resumed, const RunResult& whole) {
  REQUIRE(resumed.summary.complete);
  REQUIRE(resumed.events.size() == whole.events.size());
  for (std::size_t i = 0; i < whole.events.size(); ++i) {
    const BreakEvent& a = resumed.events[i];
    const BreakEvent& b = whole.events[i];
    INFO("event " << i);
    REQUIRE(a.bond == b.bond);
    REQUIRE(a.mode == b.mode);
    REQUIRE(a.cascade == b.cascade);
    REQUIRE(std::abs(a.lambda - b.lambda) <= 1e-12 * std::abs(b.lambda));
    REQUIRE(std::abs(a.failure_index - b.failure_index) <= 1e-12 * std::abs(b.failure_index));
  }
  REQUIRE(resumed.summary.breaks == whole.summary.breaks);
  // With friction the path matters: the slip and its work are the uninterrupted run's.
  REQUIRE(resumed.friction_work.size() == whole.friction_work.size());
  REQUIRE(std::abs(resumed.summary.friction_work - whole.summary.friction_work) <=
          1e-9 * std::abs(whole.summary.friction_work));
  REQUIRE(std::abs(resumed.summary.contact_slip - whole.summary.contact_slip) <=
          1e-9 * std::abs(whole.summary.contact_slip));
  REQUIRE(resumed.snapshots.size() == whole.snapshots.size());
  REQUIRE(resumed.fragments.size() == whole.fragments.size());
  const Snapshot& last = resumed.snapshots.back();
  const Snapshot& expected = whole.snapshots.back();
  REQUIRE(last.bond_intact == expected.bond_intact);
  for (std::size_t k = 0; k < expected.displacement.size(); ++k)
    REQUIRE(std::abs(last.displacement[k] - expected.displacement[k]) <=
            1e-9 * (std::abs(expected.displacement[k]) + 1e-3));
}

// Stops at a few chances drawn with fixed seeds, once each, and at three in one run.
void check_resumes(const Scene& scene) {
  ScratchDirectory scratch;
  const std::string path = scratch.file("run.h5");
  StopAt counter(path, 0);
  const RunResult whole = run_with(scene, &counter, nullptr);
  const long chances = counter.chances();
  REQUIRE(chances > 3);
  for (unsigned seed : {1u, 2u}) {
    std::mt19937 random(seed);
    const long stop = std::uniform_int_distribution<long>(1, chances)(random);
    INFO("seed " << seed << ": stopped at chance " << stop << " of " << chances);
    require_same_events(stopped_and_resumed(scene, {stop}, path), whole);
  }
  INFO("stopped three times");
  require_same_events(stopped_and_resumed(scene, {1, chances / 3, chances / 3}, path), whole);
}

TEST_CASE("a resumed 2-D fixed-step run gives the uninterrupted events", "[restart]") {
  check_resumes(shipped("fig6-elliptic-graben-2d.toml", {"lattice.spacing=2000"}));
  check_resumes(
      shipped("fig6-elliptic-graben-2d.toml", {"lattice.spacing=2000", "contact.enabled=true"}));
}

TEST_CASE("a resumed 2-D event-driven run gives the uninterrupted events", "[restart]") {
  check_resumes(shipped("fig4a-tensile-2d.toml",
                        {"lattice.spacing=2000", "stepping.method=event", "contact.enabled=true"}));
  check_resumes(
      shipped("fig6-elliptic-graben-2d.toml", {"lattice.spacing=2000", "stepping.method=event"}));
}

TEST_CASE("a resumed run with friction gives the uninterrupted events, slip and work",
          "[restart][friction]") {
  check_resumes(shipped("graben-complete-2d.toml", {"lattice.spacing=3000"}));
  // Many slipping contacts: the LU is replayed from the checkpoint (before it was, this
  // case drifted by 2e-6 of the displacements after three stops).
  check_resumes(shipped("fig6-elliptic-graben-2d.toml",
                        {"lattice.spacing=3000", "stepping.method=event", "contact.friction=0.6"}));
  // 3-D: contacts on facets and edges of the polyhedral cone.
  check_resumes(shipped("reference-3d.toml",
                        {"lattice.spacing=5000", "stepping.method=event", "contact.friction=0.6",
                         "loading.total=0.004", "output.snapshots=[0.002, 0.004]"}));
}

// Stops at a third and at half of the run's chances and resumes: the events' lambdas and
// the friction work are the uninterrupted run's bit for bit (compared with ==).
void check_bit_for_bit(const Scene& scene) {
  ScratchDirectory scratch;
  const std::string path = scratch.file("run.h5");
  StopAt counter(path, 0);
  const RunResult whole = run_with(scene, &counter, nullptr);
  for (long stop : {counter.chances() / 3, counter.chances() / 2}) {
    INFO("stopped at chance " << stop << " of " << counter.chances());
    const RunResult resumed = stopped_and_resumed(scene, {stop}, path);
    REQUIRE(resumed.events.size() == whole.events.size());
    for (std::size_t i = 0; i < whole.events.size(); ++i) {
      INFO("event " << i);
      REQUIRE(resumed.events[i].bond == whole.events[i].bond);
      REQUIRE(resumed.events[i].lambda == whole.events[i].lambda);
    }
    REQUIRE(resumed.summary.friction_work == whole.summary.friction_work);
  }
}

TEST_CASE("a resumed run carries the Woodbury terms of its slipping contacts along",
          "[restart][friction]") {
  // W = A^-1 U follows the factor's updates (docs/restart.md); solved afresh at the resume
  // it rounds differently, and this run's events then differed in the last bits (from
  // event 53 when stopped at chance 85). With W and the updates it has not followed in
  // the checkpoint, the resumed run is the uninterrupted one bit for bit.
  check_bit_for_bit(shipped("graben-complete-2d.toml", {"lattice.spacing=3000"}));
}

TEST_CASE("a resumed event-driven run carries its path's solve along", "[restart]") {
  // The path's Y = A^-1 [load0 load1] follows the factor's updates too, with or without
  // friction; solved afresh at the resume it would round differently.
  check_bit_for_bit(shipped("fig6-elliptic-graben-2d.toml",
                            {"lattice.spacing=2000", "stepping.method=event"}));
}

TEST_CASE("a resumed 3-D run gives the uninterrupted events", "[restart]") {
  check_resumes(shipped("reference-3d.toml", {"lattice.spacing=5000", "contact.enabled=true"}));
  check_resumes(shipped("reference-3d.toml", {"lattice.spacing=5000", "stepping.method=event"}));
}

TEST_CASE("a 3-D run that holds parts before and after the stop resumes exactly", "[restart]") {
  // The shipped 3-D reference (contact, 3000 m) holds parts all along (about 130 times):
  // each hold reuses the previous analysis's elimination order, so the resumed solver
  // must start from the same analysis for its factors to round the same way.
  const Scene scene = shipped("reference-3d.toml", {"stepping.method=event"});
  ScratchDirectory scratch;
  const std::string path = scratch.file("run.h5");
  StopAt counter(path, 0);
  const RunResult whole = run_with(scene, &counter, nullptr);
  REQUIRE(whole.fragments.size() > 20);
  require_same_events(stopped_and_resumed(scene, {counter.chances() / 2}, path), whole);
}

TEST_CASE("a checkpoint's file is an incomplete result readers can use", "[restart]") {
  ScratchDirectory scratch;
  const std::string path = scratch.file("run.h5");
  const Scene scene = shipped("fig6-elliptic-graben-2d.toml", {"lattice.spacing=2000"});
  StopAt control(path, 5);
  const RunResult stopped = run_with(scene, &control, nullptr);
  CHECK_FALSE(stopped.summary.complete);
  const RunResult read = read_result_file(path);
  CHECK_FALSE(read.summary.complete);
  CHECK(read.events.size() == stopped.events.size());
  CHECK(read.summary.final_lambda > 0);
  CHECK(read_checkpoint(path).started);

  // A finished run's file has nothing to resume.
  const RunResult whole = run_with(scene, nullptr, nullptr);
  write_result_file(path, whole);
  CHECK(read_result_file(path).summary.complete);
  CHECK_THROWS_AS(read_checkpoint(path), InputError);
}

// Rewrites a checkpoint value through HDF5 (so the checksums stay valid): what an edit,
// or damage that a checksum cannot see, would leave.
void set_checkpoint_attribute(const std::string& path, const char* name, hid_t type,
                              const void* value) {
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  REQUIRE(file >= 0);
  const hid_t group = H5Gopen2(file, "/checkpoint", H5P_DEFAULT);
  REQUIRE(group >= 0);
  const hid_t attribute = H5Aopen(group, name, H5P_DEFAULT);
  REQUIRE(attribute >= 0);
  REQUIRE(H5Awrite(attribute, type, value) >= 0);
  H5Aclose(attribute);
  H5Gclose(group);
  REQUIRE(H5Fclose(file) >= 0);
}

template <class T>
void edit_checkpoint_dataset(const std::string& path, const char* name, hid_t type,
                             const std::function<void(std::vector<T>&)>& edit) {
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  REQUIRE(file >= 0);
  const hid_t dataset = H5Dopen2(file, name, H5P_DEFAULT);
  REQUIRE(dataset >= 0);
  const hid_t space = H5Dget_space(dataset);
  std::vector<T> values(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
  H5Sclose(space);
  REQUIRE(H5Dread(dataset, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) >= 0);
  edit(values);
  REQUIRE(H5Dwrite(dataset, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) >= 0);
  H5Dclose(dataset);
  REQUIRE(H5Fclose(file) >= 0);
}

TEST_CASE("a checkpoint that does not fit its run is refused, not resumed", "[restart]") {
  // Each edit used to crash the resume (an index out of range) or let it write a file
  // that said complete without the breaks or snapshots it lacked.
  ScratchDirectory scratch;
  const std::string path = scratch.file("run.h5");
  const Scene scene = shipped("fig6-elliptic-graben-2d.toml",
                              {"lattice.spacing=3000", "stepping.method=\"event\""});
  StopAt control(path, 5);
  REQUIRE_FALSE(run_with(scene, &control, nullptr).summary.complete);
  auto resume = [&] {
    ResumePoint point;
    point.result = read_result_file(path);
    point.checkpoint = read_checkpoint(path);
    run_with(scene, nullptr, &point);
  };
  using Catch::Contains;
  SECTION("a free dof numbered out of range") {
    edit_checkpoint_dataset<std::int64_t>(path, "/checkpoint/free_index", H5T_NATIVE_INT64,
                                          [](auto& v) {
                                            for (auto& index : v)
                                              if (index >= 0) {
                                                index = 99999999;
                                                break;
                                              }
                                          });
    CHECK_THROWS_WITH(read_checkpoint(path), Contains("out of order") && Contains("damaged"));
  }
  SECTION("a pair state that does not exist") {
    edit_checkpoint_dataset<std::uint8_t>(path, "/checkpoint/pair_state", H5T_NATIVE_UINT8,
                                          [](auto& v) { v.front() = 9; });
    CHECK_THROWS_WITH(read_checkpoint(path), Contains("pair state 9"));
  }
  SECTION("more snapshots taken than the file holds") {
    const std::int64_t taken = 99;
    set_checkpoint_attribute(path, "snapshots_taken", H5T_NATIVE_INT64, &taken);
    CHECK_THROWS_WITH(resume(), Contains("snapshots were taken"));
  }
  SECTION("a lambda beyond the loading") {
    const double lambda = 1.0;
    set_checkpoint_attribute(path, "lambda", H5T_NATIVE_DOUBLE, &lambda);
    CHECK_THROWS_WITH(resume(), Contains("outside the loading"));
  }
  SECTION("a negative count") {
    const std::int64_t step = -3;
    set_checkpoint_attribute(path, "next_step", H5T_NATIVE_INT64, &step);
    CHECK_THROWS_WITH(read_checkpoint(path), Contains("negative count"));
  }
}

TEST_CASE("a result file is written by one run at a time", "[restart]") {
  ScratchDirectory scratch;
  const std::string path = scratch.file("run.h5");
  ResultWriter first(path, scratch.file("run.xmf"), 1, "p.toml", {});
  first.finish(testing::sample_result());
  ResultWriter second(path, scratch.file("run.xmf"), 1, "p.toml", {});
  CHECK_THROWS_WITH(second.finish(testing::sample_result()),
                    Catch::Contains("is being written by another latfrac run"));
}

}  // namespace
}  // namespace latfrac
