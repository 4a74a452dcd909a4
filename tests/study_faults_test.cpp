// The study's fault angles: the graben's and the pre-cut fault's, and the angles between runs'.
#include <catch2/catch.hpp>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "latfrac/analysis/fault_analysis.h"
#include "latfrac/study/study.h"
#include "synthetic_faults.h"

using namespace latfrac;
using namespace latfrac::testing;
using Catch::Matchers::Contains;

namespace {

// The columns of study.csv by name, for each row after the header.
std::vector<std::vector<std::string>> csv_rows(const std::string& csv,
                                               std::vector<std::string>& header) {
  std::vector<std::vector<std::string>> rows;
  std::stringstream lines(csv);
  for (std::string line; std::getline(lines, line);) {
    std::vector<std::string> fields;
    std::stringstream items(line);
    for (std::string field; std::getline(items, field, ',');) fields.push_back(field);
    if (line.back() == ',') fields.push_back("");
    rows.push_back(fields);
  }
  header = rows.front();
  rows.erase(rows.begin());
  return rows;
}

double column(const std::vector<std::string>& row, const std::vector<std::string>& header,
              const std::string& name) {
  const auto found = std::find(header.begin(), header.end(), name);
  REQUIRE(found != header.end());
  return std::stod(row[found - header.begin()]);
}

StudyRow row_of(const RunResult& run, const ReferenceFacts& facts, std::optional<double> ds) {
  StudyRow row;
  row.method = ds ? "fixed" : "event";
  row.reference = !ds;
  row.increment = ds;
  fill_from_run(row, run, facts);
  return row;
}

}  // namespace

TEST_CASE("The study's angles are the graben's and the pre-cut fault's, not the largest fault's",
          "[study][roles]") {
  // The reference: a V graben whose left arm dips 55 deg and whose right arm, from the
  // pre-cut's tip, 65 deg, beside a vertical wall fault larger than either arm.
  const RunResult reference = graben_with_precut(55, 65, false).result;
  const FaultReport report = analyze_faults(reference);
  REQUIRE(report.faults[0].role == FaultRole::wall);  // the largest: alpha 0, not to be read
  REQUIRE(report.faults[0].alpha_deg < 1);

  const ReferenceFacts facts = reference_facts(reference);
  REQUIRE(facts.faults.graben_left);
  REQUIRE(facts.faults.graben_right);
  REQUIRE(facts.faults.precut);
  CHECK(std::abs(facts.faults.graben_left->alpha_deg - 35) < kDipToleranceDeg);
  CHECK(std::abs(facts.faults.graben_right->alpha_deg - 25) < kDipToleranceDeg);
  CHECK(std::abs(facts.faults.precut->alpha_deg - 25) < kDipToleranceDeg);
  CHECK(facts.faults.precut->side == -1);

  // Runs: the left arm at 50 deg; the mirror image (the pre-cut fault now descends towards
  // +x); the reference itself.
  StudyResult study;
  study.rows = {row_of(reference, facts, std::nullopt),
                row_of(graben_with_precut(50, 65, false).result, facts, 1e-3),
                row_of(graben_with_precut(55, 65, true).result, facts, 1e-4),
                row_of(reference, facts, 1e-5)};
  std::vector<std::string> header;
  const auto rows = csv_rows(study_csv(study), header);
  REQUIRE(rows.size() == 4);
  // Each of two fits is within the tolerance, so their difference is within twice it.
  const double tolerance = 2 * kDipToleranceDeg;
  CHECK(column(rows[0], header, "graben_left_alpha") == Approx(35).margin(kDipToleranceDeg));
  CHECK(column(rows[0], header, "graben_left_difference") == 0);
  CHECK(column(rows[0], header, "precut_difference") == 0);
  CHECK(column(rows[1], header, "graben_left_alpha") == Approx(40).margin(kDipToleranceDeg));
  CHECK(column(rows[1], header, "graben_left_difference") == Approx(5).margin(tolerance));
  CHECK(column(rows[1], header, "graben_right_difference") < tolerance);
  CHECK(column(rows[1], header, "precut_difference") < tolerance);
  // Mirrored, the graben's left fault is the 65 deg arm, and the pre-cut fault descends the
  // other way: it lies at 25 + 25 deg to the reference's.
  CHECK(column(rows[2], header, "graben_left_alpha") == Approx(25).margin(kDipToleranceDeg));
  CHECK(column(rows[2], header, "graben_right_alpha") == Approx(35).margin(kDipToleranceDeg));
  CHECK(column(rows[2], header, "graben_left_difference") == Approx(10).margin(tolerance));
  CHECK(column(rows[2], header, "precut_difference") == Approx(50).margin(tolerance));
  CHECK(rows[0][std::find(header.begin(), header.end(), "precut_side") - header.begin()] == "-x");
  CHECK(rows[2][std::find(header.begin(), header.end(), "precut_side") - header.begin()] == "+x");

  const std::string reading = angle_interpretation(study);
  CHECK_THAT(reading, Contains("the largest increment with every fault angle within 1 deg") &&
                          Contains("is fixed ds=1e-5"));
  study.rows.pop_back();
  CHECK_THAT(angle_interpretation(study), Contains("no increment has every fault angle within"));
  CHECK_THAT(study_markdown(study), Contains("| graben alpha left / right | vs reference (deg) |"));
}

TEST_CASE("The angle between two faults", "[study]") {
  auto line = [](double dip, int side) {
    const double d = dip * M_PI / 180;
    return TrackedFault{90 - dip, side, {side * std::sin(d), 0, std::cos(d)}};
  };
  CHECK(angle_between(line(60, 1), line(55, 1)) == Approx(5));
  CHECK(angle_between(line(60, 1), line(60, -1)) == Approx(60));  // alpha 30 + 30
  CHECK(angle_between(line(20, 1), line(30, -1)) == Approx(50));  // 180 - (70 + 60)
  CHECK(angle_between(line(90, 1), line(90, -1)) == Approx(0).margin(1e-6));  // both vertical
}
