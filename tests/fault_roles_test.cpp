// Fault roles: hand-placed graben, pre-cut and wall faults give their roles, dips and sides.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <string>

#include "latfrac/analysis/fault_analysis.h"
#include "latfrac/base/error.h"
#include "synthetic_faults.h"

using namespace latfrac;
using namespace latfrac::testing;

namespace {

constexpr int kColumns = kGrabenColumns, kRows = kGrabenRows;
constexpr double kWidth = kGrabenWidth;
constexpr double kLeftDip = 55, kRightDip = 65;  // the graben's arms, deg

Layout graben_layout(bool mirrored) { return graben_with_precut(kLeftDip, kRightDip, mirrored); }

// "46 %": a share as the text report prints it.
std::string format_percent(double share) {
  char text[32];
  std::snprintf(text, sizeof text, "%.0f %%", 100 * share);
  return text;
}

std::size_t count_role(const FaultReport& report, FaultRole role) {
  return std::count_if(report.faults.begin(), report.faults.end(),
                       [&](const Fault& f) { return f.role == role; });
}

}  // namespace

TEST_CASE("The graben's faults, the pre-cut fault and the wall fault get their roles",
          "[analysis][roles]") {
  const bool mirrored = GENERATE(false, true);
  CAPTURE(mirrored);
  const Layout layout = graben_layout(mirrored);
  const FaultReport report = analyze_faults(layout.result);

  REQUIRE(report.faults.size() == 4);
  CHECK(report.precut_bonds == static_cast<std::int64_t>(layout.precut));
  CHECK(report.broken_bonds ==
        static_cast<std::int64_t>(layout.wall + layout.graben + layout.other));

  // The wall fault is the largest (listed first): the case where the largest is not the one
  // to read.
  const Fault& wall = report.faults[0];
  CHECK(wall.role == FaultRole::wall);
  CHECK(wall.bonds == static_cast<std::int64_t>(layout.wall));
  CHECK(wall.bonds > report.faults[1].bonds);
  CHECK(wall.wall_share == 1.0);
  CHECK(std::abs(wall.centroid[0] - (mirrored ? kWidth : 0)) < 1.4);
  CHECK(count_role(report, FaultRole::wall) == 1);
  CHECK(count_role(report, FaultRole::other) == 1);
  CHECK(count_role(report, FaultRole::precut) == 0);  // the pre-cut fault is a graben fault

  // The graben: its left fault dips towards +x, its right one towards -x. Unmirrored the
  // left arm dips 55 deg and the right one (from the pre-cut) 65; mirrored, the reverse.
  REQUIRE(report.graben);
  const Graben& graben = report.grabens[*report.graben];
  const Fault& left = report.faults[graben.left_fault];
  const Fault& right = report.faults[graben.right_fault];
  CHECK(left.role == FaultRole::graben);
  CHECK(right.role == FaultRole::graben);
  CHECK(left.dip_direction == 1);
  CHECK(right.dip_direction == -1);
  CHECK(std::abs(left.dip_deg - (mirrored ? kRightDip : kLeftDip)) < kDipToleranceDeg);
  CHECK(std::abs(right.dip_deg - (mirrored ? kLeftDip : kRightDip)) < kDipToleranceDeg);
  CHECK(left.alpha_deg == Approx(90 - left.dip_deg));
  CHECK(left.bonds + right.bonds == static_cast<std::int64_t>(layout.graben));
  CHECK(graben.surface_subsidence == Approx(10.0).epsilon(0.01));
  // The bonds off the graben's faults, counted from the layout: the wall fault's and the
  // other cluster's.
  const double outside = static_cast<double>(layout.wall + layout.other) /
                         static_cast<double>(layout.wall + layout.graben + layout.other);
  CHECK(share_outside_graben(report) == Approx(outside).epsilon(1e-12));
  CHECK(outside > 0.1);
  CHECK(outside < 0.9);

  // The pre-cut fault leaves the cut's tip: the right arm, or the left one mirrored.
  REQUIRE(report.precut_fault);
  CHECK(*report.precut_fault == (mirrored ? graben.left_fault : graben.right_fault));
  CHECK(report.faults[*report.precut_fault].precut_distance < 1.5);
  CHECK(wall.precut_distance > 40);

  const std::string json = to_json(report);
  CHECK(json.find("\"graben\": {\"index\": " + std::to_string(*report.graben) +
                  ", \"faults\": [{\"fault\": " + std::to_string(graben.left_fault) +
                  ", \"side\": \"+x\"") != std::string::npos);
  CHECK(json.find("\"precut_fault\": {\"fault\": " + std::to_string(*report.precut_fault) +
                  ", \"side\": \"" + (mirrored ? "+x" : "-x") + "\"") != std::string::npos);
  CHECK(json.find("\"role\": \"wall\"") != std::string::npos);
  CHECK(json.find("\"share_outside\": ") != std::string::npos);
  const std::string text = to_text(report);
  CHECK(text.find(format_percent(outside) + " of the broken bonds outside these two") !=
        std::string::npos);
  CHECK(text.find("pre-cut fault: " + std::to_string(*report.precut_fault + 1) + " (dips to " +
                  (mirrored ? "+x" : "-x")) != std::string::npos);
  CHECK(text.find("wall faults: 1\n") != std::string::npos);
}

TEST_CASE("A mirrored layout gives the mirrored sides and the same dips", "[analysis][roles]") {
  const FaultReport plain = analyze_faults(graben_layout(false).result);
  const FaultReport mirrored = analyze_faults(graben_layout(true).result);
  REQUIRE(plain.faults.size() == mirrored.faults.size());
  for (std::size_t f = 0; f < plain.faults.size(); ++f) {
    CAPTURE(f);
    const Fault& a = plain.faults[f];
    const Fault& b = mirrored.faults[f];
    CHECK(a.role == b.role);
    CHECK(a.bonds == b.bonds);
    CHECK(a.dip_deg == Approx(b.dip_deg).margin(1e-9));
    CHECK(a.dip_direction == -b.dip_direction);
    CHECK(a.centroid[0] == Approx(kWidth - b.centroid[0]).margin(1e-9));
  }
  REQUIRE(plain.graben);
  REQUIRE(mirrored.graben);
  const Graben& g = plain.grabens[*plain.graben];
  const Graben& h = mirrored.grabens[*mirrored.graben];
  CHECK(g.left_fault == h.right_fault);
  CHECK(g.right_fault == h.left_fault);
  CHECK(*plain.precut_fault == *mirrored.precut_fault);
}

TEST_CASE("A fault is a wall fault when most of it lies within 3 spacings of a side wall",
          "[analysis][roles]") {
  // A vertical band centred `offset` m from the wall: its points lie within offset + 0.5.
  const auto [offset, wall] =
      GENERATE(table<double, bool>({{1.2, true}, {2.2, true}, {4.2, false}}));
  const bool right_wall = GENERATE(false, true);
  CAPTURE(offset, right_wall);
  RunResult result = triangular(kColumns, kRows, true);
  const double x = right_wall ? kWidth - offset : offset;
  break_where(result, [&](const Xyz& m) { return std::abs(m[0] - x) < 0.5 && m[2] > 4; });
  const FaultReport report = analyze_faults(result);
  REQUIRE(report.faults.size() == 1);
  CHECK((report.faults[0].role == FaultRole::wall) == wall);
  CHECK(report.faults[0].wall_share == (wall ? 1.0 : 0.0));
  CHECK_FALSE(report.precut_fault);
  CHECK(report.precut_bonds == 0);
  CHECK(std::isinf(report.faults[0].precut_distance));
  const std::string json = to_json(report);
  CHECK(json.find("\"graben\": null, \"precut_fault\": null") != std::string::npos);
  CHECK(to_text(report).find("pre-cut fault: none (the run has no pre-cut)") != std::string::npos);
  CHECK(share_outside_graben(report) == 1.0);  // no graben: every broken bond is off it
}

TEST_CASE("A graben fault reaching the surface at the wall's corner is no wall fault",
          "[analysis][roles]") {
  // Fig. 6 with contact: one graben fault leaves the surface where a wall fault ends.
  RunResult result = triangular(kColumns, kRows, true);
  const double top = top_z(result);
  const double depth = 24, dip = 60, half_width = depth / std::tan(dip * kDegree);
  const auto wall = break_where(result, [](const Xyz& m) { return m[0] < 0.9; });
  const auto arms = break_along(
      result, {{1.0, top}, {1.0 + half_width, top - depth}, {1.0 + 2 * half_width, top}});
  const FaultReport report = analyze_faults(result);
  REQUIRE(report.graben);
  const Graben& graben = report.grabens[*report.graben];
  const Fault& left = report.faults[graben.left_fault];
  CHECK(std::abs(left.dip_deg - dip) < kDipToleranceDeg);
  CHECK(left.wall_share < 0.5);
  CHECK(std::abs(report.faults[graben.right_fault].dip_deg - dip) < kDipToleranceDeg);
  REQUIRE(count_role(report, FaultRole::wall) == 1);
  CHECK(count_role(report, FaultRole::graben) == 2);
}

TEST_CASE("A fault along a wall bounds no graben", "[analysis][roles]") {
  // A left fault dipping 60 deg towards +x, and a steep one dipping towards -x that hugs the
  // right wall: inclined enough to pair, but a wall fault.
  RunResult result = triangular(kColumns, kRows, true);
  const double top = top_z(result);
  break_along(result, {{50, top}, {50 + 12 / std::tan(60 * kDegree), top - 12}});
  break_along(result,
              {{kWidth - 0.6, top}, {kWidth - 0.6 - 12 / std::tan(75 * kDegree), top - 12}});
  const FaultReport report = analyze_faults(result);
  REQUIRE(report.faults.size() == 2);
  CHECK(count_role(report, FaultRole::wall) == 1);
  CHECK(report.grabens.empty());
  CHECK_FALSE(report.graben);
  // Counted as no wall fault (all its points would have to lie near the wall), it pairs.
  FaultOptions options;
  options.wall_share = 1;
  CHECK(analyze_faults(result, kLastSnapshot, options).grabens.size() == 1);
}

TEST_CASE("Nested faults give the innermost graben, and a fault outside the block hides none",
          "[analysis][roles]") {
  RunResult result = triangular(kColumns, kRows, true);
  const double top = top_z(result);
  const double cot60 = 1 / std::tan(60 * kDegree);
  // Upper 12 m of faults dipping 60 deg: towards +x from x = 15 and 20, towards -x from 40.
  auto arm = [&](double x, int side) {
    return break_along(result, {{x, top}, {x + side * 12 * cot60, top - 12}}).size();
  };
  arm(15, 1);
  arm(20, 1);
  arm(40, -1);
  // Below and right of the block, a fault dipping towards +x whose trace, extended, reaches
  // the surface at x = 30, between the graben's traces.
  break_along(result, {{30 + (top - 14) * cot60, 14}, {30 + (top - 4) * cot60, 4}});
  const FaultReport report = analyze_faults(result);
  REQUIRE(report.faults.size() == 4);
  REQUIRE(report.grabens.size() == 1);
  const Graben& graben = report.grabens[0];
  CHECK(graben.left_surface_x == Approx(20).margin(0.5));
  CHECK(graben.right_surface_x == Approx(40).margin(0.5));
  CHECK(report.graben == 0u);
}

TEST_CASE("Wall options out of range are input errors", "[analysis][roles]") {
  const RunResult result = triangular(20, 10);
  FaultOptions options;
  options.wall_share = 0;
  CHECK_THROWS_AS(analyze_faults(result, kLastSnapshot, options), InputError);
  options.wall_share = 1.5;
  CHECK_THROWS_AS(analyze_faults(result, kLastSnapshot, options), InputError);
  options = {};
  options.wall_distance_spacings = -1;
  CHECK_THROWS_WITH(analyze_faults(result, kLastSnapshot, options), Catch::Contains("wall"));
}
