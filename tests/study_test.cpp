// The convergence study: rows against independently computed errors, the files it writes,
// the broken-set difference on hand-made sets, --increments parsing, the interpretation.
#include "latfrac/study/study.h"

#include <unistd.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "latfrac/base/error.h"
#include "latfrac/base/stop_signal.h"
#include "latfrac/scene/run.h"
#include "scenes.h"

namespace fs = std::filesystem;
using namespace latfrac;
using Catch::Matchers::Contains;

namespace {

// A 20 m x 10 m strip pulled to lambda = 1e-3; its bonds start failing near sigma0 / E = 5e-4.
Scene strip_scene() {
  Scene scene = testing::box_scene(2, 1.0, {20.0, 0, 10.0}, false);
  scene.strength = testing::strength_of(Criterion::tensile, 50e6);
  scene.loading.total = 1e-3;
  return scene;
}

RunResult fixed_run(Scene scene, double increment) {
  scene.stepping = {SteppingMethod::fixed, increment};
  scene.output.snapshots = {scene.loading.total};
  return run_scene(scene, {});
}

double first_break(const RunResult& run) {
  for (const BreakEvent& e : run.events)
    if (e.mode != BreakMode::precut) return e.lambda;
  FAIL("the run breaks nothing");
  return 0;
}

std::set<std::int64_t> broken_at_end(const RunResult& run) {
  std::set<std::int64_t> broken;
  const auto& intact = run.snapshots.back().bond_intact;
  for (std::size_t b = 0; b < intact.size(); ++b)
    if (!intact[b]) broken.insert(static_cast<std::int64_t>(b));
  return broken;
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream stream(line);
  std::string field;
  while (std::getline(stream, field, ',')) fields.push_back(field);
  if (!line.empty() && line.back() == ',') fields.push_back("");
  return fields;
}

std::vector<std::vector<std::string>> read_csv(const fs::path& path) {
  std::ifstream file(path);
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(file, line);) rows.push_back(split(line));
  return rows;
}

std::uint32_t big_endian(const unsigned char* bytes) {
  return (std::uint32_t(bytes[0]) << 24) | (std::uint32_t(bytes[1]) << 16) |
         (std::uint32_t(bytes[2]) << 8) | bytes[3];
}

StudyRow made_row(const std::string& method, std::optional<double> increment, double difference,
                  double seconds, std::int64_t solves) {
  StudyRow row;
  row.method = method;
  row.increment = increment;
  row.broken_set_difference = difference;
  row.wall_seconds = seconds;
  row.solves = solves;
  return row;
}

}  // namespace

TEST_CASE("A study's rows match errors computed from the runs themselves", "[study]") {
  const Scene scene = strip_scene();
  StudyOptions options;
  options.increments = {1e-3, 1e-4};
  options.reference_increment = 1e-5;  // switch to the event-driven reference: see below
  std::vector<std::string> reported;
  options.on_row = [&](const StudyRow& row) { reported.push_back(progress_line(row)); };
  const StudyResult study = run_study(scene, options);

  const fs::path dir =
      fs::temp_directory_path() / ("latfrac_study_test_" + std::to_string(getpid()));
  fs::remove_all(dir);
  write_study(study, dir.string());

  // study.csv: a header and one row per run, the reference first.
  const auto csv = read_csv(dir / "study.csv");
  REQUIRE(csv.size() == 4);
  const std::vector<std::string> header{"role",
                                        "method",
                                        "increment",
                                        "status",
                                        "breaks",
                                        "first_break_lambda",
                                        "first_break_error",
                                        "broken_set_difference",
                                        "graben_left_alpha",
                                        "graben_right_alpha",
                                        "precut_alpha",
                                        "precut_side",
                                        "graben_left_difference",
                                        "graben_right_difference",
                                        "precut_difference",
                                        "wall_seconds",
                                        "solves",
                                        "note"};
  CHECK(csv[0] == header);
  for (std::size_t r = 1; r < csv.size(); ++r) {
    REQUIRE(csv[r].size() == header.size());
    CHECK(csv[r][3] == "ok");
    // The strip has no pre-cut: no pre-cut fault, nothing to compare it with.
    for (const std::size_t c : {10, 11, 14}) CHECK(csv[r][c] == "");
    CHECK(std::stod(csv[r][15]) > 0);
    CHECK(std::stoll(csv[r][16]) > 0);
  }
  CHECK(csv[1][0] == "reference");
  CHECK(csv[1][1] == "fixed");
  CHECK(std::stod(csv[1][2]) == 1e-5);
  CHECK(std::stod(csv[1][6]) == 0);
  CHECK(std::stod(csv[1][7]) == 0);
  CHECK(csv[2][1] == "fixed");
  CHECK(std::stod(csv[2][2]) == 1e-3);
  CHECK(std::stod(csv[3][2]) == 1e-4);
  CHECK(reported.size() == 3);
  CHECK_THAT(reported[1], Contains("fixed ds=1e-3: ") && Contains(" breaks, "));

  // The coarse run's errors, from the two runs made here (deterministic, so identical).
  const RunResult reference = fixed_run(scene, 1e-5), coarse = fixed_run(scene, 1e-3);
  const double lambda_ref = first_break(reference), lambda_coarse = first_break(coarse);
  CHECK(std::stod(csv[2][5]) == lambda_coarse);
  CHECK(std::stod(csv[2][6]) ==
        Approx(std::abs(lambda_coarse - lambda_ref) / lambda_ref).epsilon(1e-14));
  CHECK(std::stod(csv[2][6]) > 0);
  const auto ref_broken = broken_at_end(reference), coarse_broken = broken_at_end(coarse);
  REQUIRE(!ref_broken.empty());
  std::size_t differ = 0;
  for (auto b : coarse_broken) differ += !ref_broken.count(b);
  for (auto b : ref_broken) differ += !coarse_broken.count(b);
  CHECK(std::stod(csv[2][7]) == Approx(double(differ) / ref_broken.size()).epsilon(1e-14));
  CHECK(std::stoll(csv[1][4]) == static_cast<long long>(ref_broken.size()));
  CHECK(std::stoll(csv[2][4]) == static_cast<long long>(coarse_broken.size()));

  // study.md: the scene, the table, the reading.
  std::ifstream md_file(dir / "study.md");
  const std::string md((std::istreambuf_iterator<char>(md_file)), std::istreambuf_iterator<char>());
  CHECK_THAT(md, Contains("# Convergence study: test") &&
                     Contains("| fixed (reference) | 1e-5 |") && Contains("| fixed | 1e-3 |") &&
                     Contains("## Reading") && Contains("- date: "));

  // study.png: a PNG signature and an IHDR of a sensible size.
  std::ifstream png(dir / "study.png", std::ios::binary);
  unsigned char head[24] = {};
  png.read(reinterpret_cast<char*>(head), sizeof head);
  REQUIRE(png.gcount() == 24);
  const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  CHECK(std::equal(signature, signature + 8, head));
  CHECK(std::string(reinterpret_cast<char*>(head + 12), 4) == "IHDR");
  CHECK(big_endian(head + 16) >= 400);
  CHECK(big_endian(head + 16) <= 4000);
  CHECK(big_endian(head + 20) >= 300);
  CHECK(big_endian(head + 20) <= 4000);

  // Nothing half-written is left.
  for (const auto& entry : fs::directory_iterator(dir))
    CHECK(entry.path().extension() != ".partial");
  fs::remove_all(dir);
}

TEST_CASE("With the event-driven reference a fine fixed step breaks first within one increment",
          "[study]") {
  StudyOptions options;
  options.increments = {1e-4};
  const StudyResult study = run_study(strip_scene(), options);
  REQUIRE(study.rows.size() == 2);
  const StudyRow& reference = study.rows[0];
  CHECK(reference.method == "event");
  CHECK(!reference.increment);
  CHECK(*reference.broken_set_difference == 0);
  REQUIRE(reference.first_break_lambda);
  const StudyRow& fixed = study.rows[1];
  REQUIRE(fixed.first_break_lambda);
  CHECK(*fixed.first_break_lambda >= *reference.first_break_lambda);
  CHECK(*fixed.first_break_lambda < *reference.first_break_lambda + 1e-4);
  CHECK(*fixed.first_break_error < 1e-4 / *reference.first_break_lambda);
}

TEST_CASE("A run this version cannot make is a row, not a failed study", "[study]") {
  StudyOptions options;
  options.increments = {1e-3};
  options.reference_increment = 1e-4;
  options.relaxation = true;
  const StudyResult study = run_study(strip_scene(), options);
  REQUIRE(study.rows.size() == 3);
  const StudyRow& relaxation = study.rows[2];
  CHECK(relaxation.method == "fixed+relaxation");
  CHECK(relaxation.status != RunStatus::failed);
  if (relaxation.status == RunStatus::not_available) {
    CHECK_THAT(relaxation.note, Contains("relaxation"));
    CHECK_THAT(study_csv(study), Contains(",not available,"));
    CHECK_THAT(progress_line(relaxation), Contains("fixed+relaxation ds=1e-3: not available: "));
  }
}

TEST_CASE("A stop asked for during a study ends it after the runs already done", "[study]") {
  // As SIGINT would between the reference and the first fixed-step run: that run stops at
  // its first chance, leaves no row, and the later ones do not start.
  StudyOptions options;
  options.increments = {1e-4, 5e-5};
  options.on_row = [](const StudyRow&) { request_stop(); };
  const StudyResult study = run_study(strip_scene(), options);
  clear_stop_request();
  CHECK(study.stopped);
  REQUIRE(study.rows.size() == 1);
  CHECK(study.rows[0].reference);
  // Without the request the same study runs whole.
  options.on_row = nullptr;
  const StudyResult whole = run_study(strip_scene(), options);
  CHECK_FALSE(whole.stopped);
  CHECK(whole.rows.size() == 3);
}

TEST_CASE("An increment that would take more than 1e9 steps is refused before the reference",
          "[study]") {
  // 1e-300 used to overflow the step counter: no step, 0 breaks, a row that looked real.
  const Scene scene = strip_scene();
  StudyOptions options;
  options.increments = {1e-3, 1e-300};
  std::vector<StudyRow> rows;
  options.on_row = [&](const StudyRow& row) { rows.push_back(row); };
  CHECK_THROWS_WITH(run_study(scene, options),
                    Contains("--increments: the increment = 1e-300") && Contains("at most 1e9"));
  CHECK(rows.empty());  // refused before the reference ran
  // run_scene refuses it too (a scene built in code); by hand, |total| / 1e9 is the
  // smallest increment allowed: a hair above it passes, a hair below it does not.
  Scene fixed = scene;
  fixed.stepping = {SteppingMethod::fixed, 1e-300};
  CHECK_THROWS_WITH(run_scene(fixed, RunOptions{}), Contains("stepping.increment = 1e-300"));
  CHECK_NOTHROW(check_step_count(fixed.loading.total, std::abs(fixed.loading.total) / 0.999e9, "x"));
  CHECK_THROWS(check_step_count(fixed.loading.total, std::abs(fixed.loading.total) / 1.001e9, "x"));
}

TEST_CASE("The broken-set difference on hand-made sets", "[study]") {
  CHECK(broken_set_difference({1, 2, 3}, {2, 3, 4}) == Approx(2.0 / 3.0));
  CHECK(broken_set_difference({1, 2, 3}, {1, 2, 3}) == 0);
  CHECK(broken_set_difference({}, {}) == 0);
  CHECK(broken_set_difference({}, {1, 2, 3, 4}) == 1);
  CHECK(broken_set_difference({1, 2, 3, 4, 5, 6, 7, 8}, {1, 2, 3, 4}) == 1);
  // A reference that breaks nothing: the count of bonds the run broke.
  CHECK(broken_set_difference({5, 7}, {}) == 2);
}

TEST_CASE("Increment lists (--increments): what parses and what is refused", "[study]") {
  CHECK(parse_increments("1e-2,3e-3,1e-3") == std::vector<double>{1e-2, 3e-3, 1e-3});
  CHECK(parse_increments(" 1e-3 , 0.5 ") == std::vector<double>{1e-3, 0.5});
  CHECK(parse_increments("2e-4") == std::vector<double>{2e-4});
  for (const std::string bad :
       {"", "  ", "abc", "1e-3,", ",1e-3", "1e-3,,1e-4", "0", "-1e-3", "nan", "inf", "1e-3x",
        "1e-3;1e-4", "1e-400", "1e-3,1e-3", "1e308", "1e-2,1.5"}) {
    INFO("--increments " << bad);
    CHECK_THROWS_AS(parse_increments(bad), InputError);
    CHECK_THROWS_WITH(parse_increments(bad), Contains("--increments: ") && Contains("allowed: "));
  }
  CHECK_THROWS_WITH(parse_increments("1e-3,abc"), Contains("'abc' is not a number"));
  CHECK_THROWS_WITH(parse_increments("-1e-3"), Contains("'-1e-3' is not a positive finite number"));
  CHECK(parse_increments("1") == std::vector<double>{1.0});
  CHECK_THROWS_WITH(parse_increments("1e308"), Contains("'1e308' is a strain step above 1"));
  CHECK_THROWS_WITH(parse_increments("1e-3,,1e-4"), Contains("item 2 is empty"));
}

TEST_CASE("Increments are labelled as short as they read back", "[study]") {
  CHECK(increment_text(1e-3) == "1e-3");
  CHECK(increment_text(3e-3) == "3e-3");
  CHECK(increment_text(2.5e-4) == "2.5e-4");
  CHECK(increment_text(0.5) == "5e-1");
  CHECK(increment_text(1) == "1");
}

TEST_CASE("The reading names the largest increment that matches the reference", "[study]") {
  StudyResult study;
  study.rows.push_back(made_row("event", std::nullopt, 0, 10, 1000));
  study.rows.back().reference = true;
  study.rows.push_back(made_row("fixed", 1e-2, 0.5, 1, 100));
  study.rows.push_back(made_row("fixed", 1e-3, 0, 5, 400));
  study.rows.push_back(made_row("fixed", 1e-4, 0, 20, 2000));
  auto reading = study_interpretation(study);
  REQUIRE(reading.size() == 3);
  CHECK_THAT(reading[0], Contains("exactly is fixed ds=1e-3"));
  CHECK_THAT(reading[2], Contains("the reference has no graben and no pre-cut fault"));
  CHECK_THAT(reading[1], Contains("5 s and 400 solves") &&
                             Contains("0.5 times the reference's wall time (10 s)") &&
                             Contains("0.4 times its solves (1000)"));

  study.rows[2].broken_set_difference = 0.004;
  study.rows[3].broken_set_difference = 0.02;
  reading = study_interpretation(study);
  CHECK_THAT(reading[0], Contains("within 1 % is fixed ds=1e-3") && Contains("0.4 %"));

  study.rows[2].broken_set_difference = 0.03;
  reading = study_interpretation(study);
  CHECK_THAT(reading[0], Contains("No increment comes within 1 %") && Contains("fixed ds=1e-4"));
}
