// Fault analysis: synthetic broken-bond sets of known geometry, against their angles and counts.
#include "latfrac/analysis/fault_analysis.h"

#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <random>

#include "latfrac/base/error.h"
#include "synthetic_faults.h"

using namespace latfrac;
using namespace latfrac::testing;

namespace {

std::int64_t total_bonds(const FaultReport& report) {
  std::int64_t total = 0;
  for (const Fault& fault : report.faults) total += fault.bonds;
  return total;
}

// Exactly two faults, neither diffuse, both at `dip` within 1 degree, holding all `marked`
// bonds between them.
void check_two_faults(const FaultReport& report, double dip, std::size_t marked) {
  REQUIRE(report.faults.size() == 2);
  CHECK(total_bonds(report) == static_cast<std::int64_t>(marked));
  for (const Fault& fault : report.faults) {
    CHECK(std::abs(fault.dip_deg - dip) < 1.0);
    CHECK_FALSE(fault.diffuse);
  }
}

// The number of clusters, splitting none.
std::size_t cluster_count(const RunResult& result) {
  FaultOptions unsplit;
  unsplit.max_split_depth = 0;
  return analyze_faults(result, kLastSnapshot, unsplit).faults.size();
}

// Structural checks that need nothing outside the test: balanced brackets outside strings,
// no NaN or infinity.
void check_json_shape(const std::string& json) {
  int depth = 0;
  bool in_string = false;
  for (const char c : json) {
    if (c == '"') in_string = !in_string;
    if (in_string) continue;
    if (c == '{' || c == '[') ++depth;
    if (c == '}' || c == ']') --depth;
    REQUIRE(depth >= 0);
  }
  CHECK(depth == 0);
  CHECK_FALSE(in_string);
  CHECK(json.front() == '{');
  CHECK(json.back() == '}');
  std::string lower = json;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  CHECK(lower.find("nan") == std::string::npos);
  CHECK(lower.find("inf") == std::string::npos);
}

// Parses the text with Python's json module when python3 is installed.
void check_json_with_python(const std::string& json) {
  if (std::system("python3 -c pass > /dev/null 2>&1") != 0) {
    WARN("python3 not found: JSON checked for shape only");
    return;
  }
  const auto path = std::filesystem::temp_directory_path() /
                    ("latfrac-fault-json-" + std::to_string(std::random_device{}()) + ".json");
  std::ofstream(path) << json;
  const std::string command =
      "python3 -c 'import json, sys; json.load(open(sys.argv[1]))' '" + path.string() + "'";
  CHECK(std::system(command.c_str()) == 0);
  std::filesystem::remove(path);
}

}  // namespace

TEST_CASE("A straight band of broken bonds gives its dip", "[analysis]") {
  // angle: the line rises towards +x at this angle; a line rising towards +x descends
  // towards -x.
  const auto [angle, expected_direction] = GENERATE(
      table<double, int>({{30.0, -1}, {60.0, -1}, {75.0, -1}, {90.0, 0}, {120.0, 1}, {105.0, 1}}));
  CAPTURE(angle);
  RunResult result = triangular();
  const auto marked = break_where(
      result, [&](const Xyz& m) { return distance_to_line(m, 30.0, 17.0, angle) < 0.5; });
  const FaultReport report = analyze_faults(result);

  const double dip = angle <= 90 ? angle : 180 - angle;
  CHECK(report.broken_bonds == static_cast<std::int64_t>(marked.size()));
  REQUIRE(report.faults.size() == 1);
  const Fault& fault = report.faults[0];
  CHECK(fault.bonds == static_cast<std::int64_t>(marked.size()));
  CHECK(std::abs(fault.dip_deg - dip) < 1.0);
  CHECK(fault.alpha_deg == Approx(90.0 - fault.dip_deg));
  CHECK(fault.dip_direction == expected_direction);
  CHECK_FALSE(fault.diffuse);
  CHECK(fault.fit_rms < 0.5);
  CHECK(report.lambda == 0.04);
  CHECK(report.grabens.empty());
  if (angle == 90.0) CHECK(std::abs(fault.extent - top_z(result)) < 1.0);
}

TEST_CASE("A plane of broken bonds in 3-D gives its dip", "[analysis]") {
  // The plane's upward normal tilts by the dip towards the azimuth (from +x towards +y) it
  // descends to.
  const auto [dip, azimuth, expected_direction] =
      GENERATE(table<double, double, int>({{50.0, 0.0, 1}, {35.0, 160.0, -1}, {70.0, -20.0, 1}}));
  CAPTURE(dip, azimuth);
  const Xyz normal{std::sin(dip * kDegree) * std::cos(azimuth * kDegree),
                   std::sin(dip * kDegree) * std::sin(azimuth * kDegree), std::cos(dip * kDegree)};
  RunResult result = cubic();
  const auto marked = break_where(result, [&](const Xyz& m) {
    return std::abs((m[0] - 7.3) * normal[0] + (m[1] - 7.6) * normal[1] +
                    (m[2] - 7.4) * normal[2]) < 0.5;
  });
  const FaultReport report = analyze_faults(result);

  REQUIRE(report.faults.size() == 1);
  const Fault& fault = report.faults[0];
  CHECK(report.dim == 3);
  CHECK(fault.bonds == static_cast<std::int64_t>(marked.size()));
  CHECK(std::abs(fault.dip_deg - dip) < 1.0);
  CHECK(fault.alpha_deg == Approx(90.0 - fault.dip_deg));
  CHECK(fault.dip_direction == expected_direction);
  CHECK_FALSE(fault.diffuse);
  CHECK(fault.extent > 15.0 * 15.0);  // the plane crosses the whole 15 x 15 m block
}

TEST_CASE("Two faults dipping towards each other bound a subsided graben", "[analysis]") {
  RunResult result = triangular();
  const double top = top_z(result);
  const double dip = 60.0;
  // The traces reach the surface at x = 20 and x = 40 and meet 10 tan(60) m below it.
  auto left_x = [&](double z) { return 20.0 + (top - z) / std::tan(dip * kDegree); };
  auto right_x = [&](double z) { return 40.0 - (top - z) / std::tan(dip * kDegree); };
  const double apex_depth = 10.0 * std::tan(dip * kDegree);
  const double apex_z = top - apex_depth;
  const auto marked = break_where(result, [&](const Xyz& m) {
    if (m[2] < apex_z + 4.0) return false;  // keep the two faults apart near the apex
    return distance_to_line(m, 20.0, top, -dip) < 0.5 || distance_to_line(m, 40.0, top, dip) < 0.5;
  });
  auto& displacement = result.snapshots.back().displacement;
  for (std::size_t i = 0; i < result.node_count(); ++i) {
    const double x = result.positions[3 * i], z = result.positions[3 * i + 2];
    if (z > apex_z && x > left_x(z) && x < right_x(z)) displacement[3 * i + 2] = -10.0;
  }
  const FaultReport report = analyze_faults(result);

  REQUIRE(report.faults.size() == 2);
  for (const Fault& fault : report.faults) CHECK(std::abs(fault.dip_deg - dip) < 1.0);
  CHECK(report.faults[0].bonds + report.faults[1].bonds ==
        static_cast<std::int64_t>(marked.size()));
  REQUIRE(report.grabens.size() == 1);
  const Graben& graben = report.grabens[0];
  const Fault& left = report.faults[graben.left_fault];
  const Fault& right = report.faults[graben.right_fault];
  CHECK(left.dip_direction == 1);
  CHECK(right.dip_direction == -1);
  CHECK(left.centroid[0] < right.centroid[0]);
  CHECK(graben.left_surface_x == Approx(20.0).margin(0.5));
  CHECK(graben.right_surface_x == Approx(40.0).margin(0.5));
  CHECK(graben.apex_depth == Approx(apex_depth).margin(1.5));
  CHECK(graben.surface_subsidence == Approx(10.0).epsilon(0.01));
  check_json_shape(to_json(report));
  CHECK(to_text(report).find("Grabens") != std::string::npos);
}

TEST_CASE("Two faults dipping away from each other are no graben", "[analysis]") {
  RunResult result = triangular();
  const double top = top_z(result);
  break_where(result, [&](const Xyz& m) {
    return distance_to_line(m, 20.0, top, 60.0) < 0.5 ||
           distance_to_line(m, 40.0, top, -60.0) < 0.5;
  });
  const FaultReport report = analyze_faults(result);
  REQUIRE(report.faults.size() == 2);
  CHECK(report.grabens.empty());
}

TEST_CASE("Nothing broken: no faults, no graben, valid JSON", "[analysis]") {
  const RunResult result = triangular(20, 10);
  const FaultReport report = analyze_faults(result);
  CHECK(report.broken_bonds == 0);
  CHECK(report.faults.empty());
  CHECK(report.grabens.empty());
  const std::string json = to_json(report);
  check_json_shape(json);
  check_json_with_python(json);
  CHECK(json.find("\"faults\": []") != std::string::npos);
  CHECK_FALSE(to_text(report).empty());
}

TEST_CASE("Snapshots: the last by default, an index out of range or none is an input error",
          "[analysis]") {
  RunResult result = triangular(30, 20);
  result.snapshots.push_back(result.snapshots.back());
  result.snapshots.back().lambda = 0.05;
  const auto marked = break_where(result, [](const Xyz& m) { return std::abs(m[0] - 15.2) < 0.5; });
  CHECK(analyze_faults(result).faults.size() == 1);
  CHECK(analyze_faults(result).lambda == 0.05);
  CHECK(analyze_faults(result, 1).broken_bonds == static_cast<std::int64_t>(marked.size()));
  CHECK(analyze_faults(result, 0).broken_bonds == 0);
  CHECK_THROWS_AS(analyze_faults(result, 2), InputError);
  result.snapshots.clear();
  CHECK_THROWS_AS(analyze_faults(result), InputError);
}

TEST_CASE("Break modes give the shares, and pre-cuts are left out", "[analysis]") {
  RunResult result = triangular();
  const auto fault_bonds =
      break_where(result, [](const Xyz& m) { return std::abs(m[0] - 40.2) < 0.5; });
  const auto precut_bonds =
      break_where(result, [](const Xyz& m) { return std::abs(m[0] - 10.2) < 0.5 && m[2] > 20.0; });
  REQUIRE(precut_bonds.size() >= 5);
  const std::size_t tensile = fault_bonds.size() / 3;
  add_events(result, {fault_bonds.begin(), fault_bonds.begin() + tensile}, 0);
  add_events(result, {fault_bonds.begin() + tensile, fault_bonds.end()}, 1);
  add_events(result, precut_bonds, 2);
  const FaultReport report = analyze_faults(result);

  CHECK(report.broken_bonds == static_cast<std::int64_t>(fault_bonds.size()));
  REQUIRE(report.faults.size() == 1);
  const Fault& fault = report.faults[0];
  CHECK(fault.tensile_share == Approx(double(tensile) / fault_bonds.size()));
  CHECK(fault.shear_share == Approx(double(fault_bonds.size() - tensile) / fault_bonds.size()));
  CHECK(fault.centroid[0] == Approx(40.2).margin(0.5));
}

TEST_CASE("A shattered region is flagged diffuse, a band beside it is not", "[analysis]") {
  RunResult result = triangular();
  break_where(result, [](const Xyz& m) { return std::hypot(m[0] - 20.0, m[2] - 17.0) < 7.0; });
  break_where(result, [](const Xyz& m) { return std::abs(m[0] - 45.2) < 0.5; });
  const FaultReport report = analyze_faults(result);
  REQUIRE(report.faults.size() == 2);
  const Fault& cloud = report.faults[0].centroid[0] < 30 ? report.faults[0] : report.faults[1];
  const Fault& band = report.faults[0].centroid[0] < 30 ? report.faults[1] : report.faults[0];
  CHECK(cloud.diffuse);
  CHECK(cloud.variance_ratio > 0.5);
  CHECK_FALSE(band.diffuse);
  CHECK(band.dip_deg == Approx(90.0).margin(1.0));
  CHECK(to_text(report).find("diffuse") != std::string::npos);
}

TEST_CASE("Small clusters are dropped, and the threshold is an option", "[analysis]") {
  RunResult result = triangular(30, 20);
  const auto marked =
      break_where(result, [](const Xyz& m) { return std::hypot(m[0] - 10.0, m[2] - 8.0) < 0.55; });
  REQUIRE(marked.size() >= 2);
  REQUIRE(static_cast<std::int64_t>(marked.size()) < FaultOptions{}.min_bonds);
  CHECK(analyze_faults(result).faults.empty());
  CHECK(analyze_faults(result).broken_bonds == static_cast<std::int64_t>(marked.size()));
  FaultOptions options;
  options.min_bonds = 1;
  CHECK(analyze_faults(result, kLastSnapshot, options).faults.size() == 1);
  options.link_distance_spacings = 0;
  CHECK_THROWS_AS(analyze_faults(result, kLastSnapshot, options), InputError);
  options = {};
  options.max_split_depth = -1;
  CHECK_THROWS_AS(analyze_faults(result, kLastSnapshot, options), InputError);
  options = {};
  options.split_rms_spacings = 0;
  CHECK_THROWS_AS(analyze_faults(result, kLastSnapshot, options), InputError);
}

TEST_CASE("JSON writes non-finite numbers as null and parses", "[analysis]") {
  FaultReport report;
  report.lambda = 0.04;
  report.broken_bonds = 12;
  Fault fault;
  fault.bonds = 12;
  fault.dip_deg = std::numeric_limits<double>::quiet_NaN();
  fault.extent = std::numeric_limits<double>::infinity();
  fault.diffuse = true;
  report.faults = {fault, fault};
  Graben graben;
  graben.right_fault = 1;
  graben.surface_subsidence = std::numeric_limits<double>::quiet_NaN();
  report.grabens = {graben};
  const std::string json = to_json(report);
  check_json_shape(json);
  check_json_with_python(json);
  CHECK(json.find("\"dip_deg\": null") != std::string::npos);
  CHECK(json.find("\"surface_subsidence\": null") != std::string::npos);
  CHECK(json.find("\"diffuse\": true") != std::string::npos);
  // The text says a subsidence it could not measure in words, not "nan".
  report.graben = 0;
  const std::string text = to_text(report);
  CHECK(text.find("subsidence not measured") != std::string::npos);
  CHECK(text.find("nan\n") == std::string::npos);
}

TEST_CASE("Two faults meeting in a V at depth are split and bound a graben", "[analysis]") {
  const double dip = GENERATE(45.0, 60.0, 75.0);
  CAPTURE(dip);
  RunResult result = triangular();
  const double top = top_z(result);
  // The arms reach the surface at 30 -/+ half_width and meet 24 m below it at x = 30.
  const double apex_depth = 24.0;
  const double half_width = apex_depth / std::tan(dip * kDegree);
  const double apex_z = top - apex_depth;
  const auto marked =
      break_along(result, {{30.0 - half_width, top}, {30.0, apex_z}, {30.0 + half_width, top}});
  auto& displacement = result.snapshots.back().displacement;
  for (std::size_t i = 0; i < result.node_count(); ++i) {
    const double x = result.positions[3 * i], z = result.positions[3 * i + 2];
    if (z > apex_z && std::abs(x - 30.0) < (z - apex_z) / std::tan(dip * kDegree)) {
      displacement[3 * i + 2] = -10.0;
    }
  }
  REQUIRE(cluster_count(result) == 1);
  const FaultReport report = analyze_faults(result);

  check_two_faults(report, dip, marked.size());
  CHECK(report.faults[0].dip_direction == -report.faults[1].dip_direction);
  REQUIRE(report.grabens.size() == 1);
  const Graben& graben = report.grabens[0];
  CHECK(report.faults[graben.left_fault].dip_direction == 1);
  CHECK(report.faults[graben.right_fault].dip_direction == -1);
  CHECK(graben.left_surface_x == Approx(30.0 - half_width).margin(0.5));
  CHECK(graben.right_surface_x == Approx(30.0 + half_width).margin(0.5));
  CHECK(graben.apex_depth == Approx(apex_depth).margin(1.0));
  CHECK(graben.surface_subsidence == Approx(10.0).epsilon(0.01));
}

TEST_CASE("An inverted V is split into its two arms", "[analysis]") {
  const double dip = GENERATE(50.0, 60.0, 70.0);
  CAPTURE(dip);
  RunResult result = triangular();
  const double top = top_z(result);
  // From a common point 3 m below the surface the arms go down and outwards to z = 2 m.
  const double apex_z = top - 3.0;
  const double spread = (apex_z - 2.0) / std::tan(dip * kDegree);
  const auto marked =
      break_along(result, {{30.0 - spread, 2.0}, {30.0, apex_z}, {30.0 + spread, 2.0}});
  REQUIRE(cluster_count(result) == 1);
  const FaultReport report = analyze_faults(result);

  REQUIRE(report.faults.size() == 2);
  CHECK(total_bonds(report) == static_cast<std::int64_t>(marked.size()));
  const Fault& left = report.faults[0].centroid[0] < 30 ? report.faults[0] : report.faults[1];
  const Fault& right = report.faults[0].centroid[0] < 30 ? report.faults[1] : report.faults[0];
  for (const Fault* fault : {&left, &right}) {
    CHECK(std::abs(fault->dip_deg - dip) < 1.0);
    CHECK_FALSE(fault->diffuse);
  }
  CHECK(left.dip_direction == -1);  // each arm descends outwards
  CHECK(right.dip_direction == 1);
  CHECK(report.grabens.empty());
}

TEST_CASE("A rough or thick straight fault is not split", "[analysis]") {
  // half_width: bonds within this of the line break. wiggle: amplitude (m) of a sideways
  // wave of 5 m wavelength along it, the roughness of a lattice crack.
  const auto [half_width, wiggle] =
      GENERATE(table<double, double>({{0.5, 0.0}, {0.5, 1.0}, {1.0, 0.7}, {2.0, 0.0}, {3.0, 0.0}}));
  CAPTURE(half_width, wiggle);
  RunResult result = triangular();
  const double dip = 60.0;
  const auto marked = break_where(result, [&](const Xyz& m) {
    const double along =
        (m[0] - 30.0) * std::cos(dip * kDegree) + (m[2] - 17.0) * std::sin(dip * kDegree);
    const double across =
        (m[0] - 30.0) * std::sin(dip * kDegree) - (m[2] - 17.0) * std::cos(dip * kDegree);
    return std::abs(across - wiggle * std::sin(2 * M_PI * along / 5.0)) < half_width;
  });
  const FaultReport report = analyze_faults(result);

  REQUIRE(report.faults.size() == 1);
  const Fault& fault = report.faults[0];
  CHECK(fault.bonds == static_cast<std::int64_t>(marked.size()));
  CHECK(std::abs(fault.dip_deg - dip) < 1.0);
  CHECK_FALSE(fault.diffuse);
  if (half_width == 3.0) CHECK(fault.fit_rms > FaultOptions{}.split_rms_spacings);  // tried
}

TEST_CASE("A shattered disc or slab stays one diffuse cluster", "[analysis]") {
  const auto [half_length, half_height] =
      GENERATE(table<double, double>({{4.0, 4.0}, {7.0, 7.0}, {12.0, 12.0}, {25.0, 8.0}}));
  CAPTURE(half_length, half_height);
  RunResult result = triangular();
  const auto marked = break_where(result, [&](const Xyz& m) {
    return std::hypot((m[0] - 30.0) / half_length, (m[2] - 17.0) / half_height) < 1.0;
  });
  const FaultReport report = analyze_faults(result);

  REQUIRE(report.faults.size() == 1);
  CHECK(report.faults[0].bonds == static_cast<std::int64_t>(marked.size()));
  CHECK(report.faults[0].diffuse);
  CHECK(report.grabens.empty());
}

TEST_CASE("A shattered ball in 3-D stays one diffuse cluster", "[analysis]") {
  RunResult result = cubic();
  const auto marked = break_where(
      result, [](const Xyz& m) { return std::hypot(m[0] - 7.5, m[1] - 7.5, m[2] - 7.5) < 5.0; });
  const FaultReport report = analyze_faults(result);

  REQUIRE(report.faults.size() == 1);
  CHECK(report.faults[0].bonds == static_cast<std::int64_t>(marked.size()));
  CHECK(report.faults[0].diffuse);
}

TEST_CASE("A zigzag crack is split into its straight segments", "[analysis]") {
  RunResult result = triangular(40, 60);
  // Three segments 15 m high, dipping 60 deg down to the right, to the left, to the right.
  const double step = 15.0 / std::tan(60.0 * kDegree);
  const auto marked =
      break_along(result, {{15.0, 48.0}, {15.0 + step, 33.0}, {15.0, 18.0}, {15.0 + step, 3.0}});
  REQUIRE(cluster_count(result) == 1);
  const FaultReport report = analyze_faults(result);

  REQUIRE(report.faults.size() == 3);
  CHECK(total_bonds(report) == static_cast<std::int64_t>(marked.size()));
  std::vector<Fault> by_depth = report.faults;
  std::sort(by_depth.begin(), by_depth.end(),
            [](const Fault& a, const Fault& b) { return a.centroid[2] > b.centroid[2]; });
  const std::array<int, 3> directions{1, -1, 1};
  for (std::size_t k = 0; k < 3; ++k) {
    CHECK(std::abs(by_depth[k].dip_deg - 60.0) < 1.0);
    CHECK(by_depth[k].dip_direction == directions[k]);
    CHECK(by_depth[k].centroid[2] == Approx(40.5 - 15.0 * k).margin(1.0));
  }
}

TEST_CASE("Two planes meeting in a V at depth in 3-D are split and bound a graben", "[analysis]") {
  const double dip = GENERATE(50.0, 60.0);
  CAPTURE(dip);
  RunResult result = cubic(20);
  const double top = top_z(result);
  // The planes run along y, reach the surface at x = 10 -/+ half_width and meet at depth.
  const double half_width = 6.0;
  const double apex_depth = half_width * std::tan(dip * kDegree);
  const double apex_z = top - apex_depth;
  const double s = std::sin(dip * kDegree), c = std::cos(dip * kDegree);
  const auto marked = break_where(result, [&](const Xyz& m) {
    if (m[2] < apex_z - 0.5) return false;
    return std::abs((m[0] - 10.0 + half_width) * s + (m[2] - top) * c) < 0.5 ||
           std::abs((m[0] - 10.0 - half_width) * s - (m[2] - top) * c) < 0.5;
  });
  REQUIRE(cluster_count(result) == 1);
  const FaultReport report = analyze_faults(result);

  check_two_faults(report, dip, marked.size());
  REQUIRE(report.grabens.size() == 1);
  const Graben& graben = report.grabens[0];
  CHECK(report.faults[graben.left_fault].dip_direction == 1);
  CHECK(report.faults[graben.right_fault].dip_direction == -1);
  CHECK(graben.left_surface_x == Approx(10.0 - half_width).margin(0.5));
  CHECK(graben.right_surface_x == Approx(10.0 + half_width).margin(0.5));
  CHECK(graben.apex_depth == Approx(apex_depth).margin(1.0));
}

// The 3-D reference block is 60 x 10 x 30 km at a 3000 m spacing: four node layers in y. These
// slabs are the same in lattice units: 40 x 4 x 20 nodes.
TEST_CASE("A thin slab shattered throughout is diffuse, not a fault along the slab", "[analysis]") {
  RunResult result = cubic_box(40, 4, 20);
  // Every bond in a 30 x 14 m window of the x-z section breaks, through the whole thickness.
  const auto marked = break_where(result, [](const Xyz& m) {
    return std::abs(m[0] - 19.5) < 15.0 && std::abs(m[2] - 9.5) < 7.0;
  });
  const FaultReport report = analyze_faults(result);

  REQUIRE(report.faults.size() == 1);
  const Fault& slab = report.faults[0];
  CHECK(slab.bonds == static_cast<std::int64_t>(marked.size()));
  CHECK(slab.diffuse);
  CHECK(report.grabens.empty());
  // The cluster is flat in y only because the slab is: the fit is the slab's mid-plane, and
  // neither the variance ratio nor the rms (m, spacing 1) tells it from a fault.
  CHECK(std::abs(slab.normal[1]) > 0.99);
  CHECK(slab.variance_ratio < FaultOptions{}.diffuse_variance_ratio);
  CHECK(slab.fit_rms < FaultOptions{}.diffuse_rms_spacings);
  // Evenly filled across the 3 m thickness: thickness sqrt(12) rms near 3 m, share near 1.
  CHECK(std::sqrt(12.0) * slab.fit_rms / 3.0 == Approx(1.0).margin(0.25));
  CHECK(slab.fill_share == Approx(std::sqrt(12.0) * slab.fit_rms / 3.0).epsilon(0.02));

  FaultOptions options;
  options.diffuse_fill_share = 2.0;  // more than the slab can fill: the old reading
  CHECK_FALSE(analyze_faults(result, kLastSnapshot, options).faults[0].diffuse);
  options.diffuse_fill_share = 0;
  CHECK_THROWS_AS(analyze_faults(result, kLastSnapshot, options), InputError);
}

TEST_CASE("A plane through the whole thickness of a thin slab is a fault with its dip",
          "[analysis]") {
  // angle: the plane's trace in the x-z section rises towards +x at this angle; the plane
  // contains the y axis, as a fault across a thin slab does.
  const auto [angle, expected_direction] =
      GENERATE(table<double, int>({{45.0, -1}, {60.0, -1}, {120.0, 1}, {90.0, 0}}));
  CAPTURE(angle);
  RunResult result = cubic_box(40, 4, 20);
  const auto marked = break_where(
      result, [&](const Xyz& m) { return distance_to_line(m, 19.3, 9.6, angle) < 0.5; });
  const FaultReport report = analyze_faults(result);

  const double dip = angle <= 90 ? angle : 180 - angle;
  REQUIRE(report.faults.size() == 1);
  const Fault& fault = report.faults[0];
  CHECK(fault.bonds == static_cast<std::int64_t>(marked.size()));
  CHECK_FALSE(fault.diffuse);
  CHECK(std::abs(fault.dip_deg - dip) < 1.0);
  CHECK(fault.dip_direction == expected_direction);
  CHECK(std::abs(fault.normal[1]) < 0.02);
}

TEST_CASE("A plane along x in a block thick in y is a fault: the rule is not an angle",
          "[analysis]") {
  // The normal is along y, as for a shattered slab, but the 15 m block is many times
  // thicker than the plane's few bonds: a vertical fault that strikes along x.
  RunResult result = cubic(16);
  const auto marked = break_where(result, [](const Xyz& m) { return std::abs(m[1] - 7.5) < 0.5; });
  const FaultReport report = analyze_faults(result);

  REQUIRE(report.faults.size() == 1);
  const Fault& fault = report.faults[0];
  CHECK(fault.bonds == static_cast<std::int64_t>(marked.size()));
  CHECK_FALSE(fault.diffuse);
  CHECK(std::abs(fault.normal[1]) > 0.999);
  CHECK(fault.dip_deg == Approx(90.0).margin(1.0));
}

namespace {

// Breaks every intact bond whose nodes lie on opposite sides of `side` (< 0 against >= 0)
// and moves the nodes on the side >= 0 by `shift`: a cut with a rigid block's motion across
// it, so every broken bond's u_j - u_i is +-shift exactly. Returns the bonds broken.
std::vector<std::int64_t> cut_and_shift(RunResult& result,
                                        const std::function<double(const Xyz&)>& side,
                                        const Xyz& shift) {
  auto node = [&](std::int64_t i) {
    return Xyz{result.positions[3 * i], result.positions[3 * i + 1], result.positions[3 * i + 2]};
  };
  Snapshot& snapshot = result.snapshots.back();
  std::vector<std::int64_t> broken;
  for (std::size_t b = 0; b < result.bond_count(); ++b) {
    const bool i_up = side(node(result.bonds[2 * b])) >= 0;
    const bool j_up = side(node(result.bonds[2 * b + 1])) >= 0;
    if (snapshot.bond_intact[b] && i_up != j_up) {
      snapshot.bond_intact[b] = 0;
      broken.push_back(static_cast<std::int64_t>(b));
    }
  }
  for (std::size_t i = 0; i < result.node_count(); ++i) {
    if (side(node(static_cast<std::int64_t>(i))) < 0) continue;
    for (int c = 0; c < 3; ++c) snapshot.displacement[3 * i + c] += shift[c];
  }
  return broken;
}

}  // namespace

TEST_CASE("A fault's offsets are its hanging wall's motion resolved on the fault", "[analysis]") {
  // A fault through (30, top) descending towards `direction` (+1: +x) at `dip`; its hanging
  // wall (the side above it) moves by `slip` down the dip and `opening` along the upward
  // normal. Every broken bond crosses the fault, so the means are the block's motion.
  const auto [dip, direction] = GENERATE(table<double, int>({{60.0, 1}, {45.0, -1}, {70.0, -1}}));
  const double opening = GENERATE(0.0, 0.4);
  CAPTURE(dip, direction, opening);
  const double slip = 2.5;
  RunResult result = triangular();
  const double top = top_z(result), c = std::cos(dip * kDegree), s = std::sin(dip * kDegree);
  const Xyz down{direction * c, 0, -s}, normal{direction * s, 0, c};
  // Above the fault: positive along the upward normal from a point on it.
  const auto above = [&](const Xyz& p) {
    return (p[0] - 30.0) * normal[0] + (p[2] - top) * normal[2];
  };
  const Xyz shift{slip * down[0] + opening * normal[0], 0, slip * down[2] + opening * normal[2]};
  const auto broken = cut_and_shift(result, above, shift);
  const FaultReport report = analyze_faults(result);

  REQUIRE(report.faults.size() == 1);
  const Fault& fault = report.faults[0];
  CHECK(fault.bonds == static_cast<std::int64_t>(broken.size()));
  CHECK(std::abs(fault.dip_deg - dip) < kDipToleranceDeg);
  CHECK(fault.dip_direction == direction);
  // The fitted line is within a degree of the cut's, so the offsets are within
  // |shift| sin(1 deg) of the cut's own.
  const double tolerance = std::hypot(slip, opening) * std::sin(kDipToleranceDeg * kDegree);
  CHECK(fault.dip_slip == Approx(slip).margin(tolerance));
  CHECK(fault.opening == Approx(opening).margin(tolerance));
  CHECK(fault.slip == Approx(slip).margin(tolerance));
  CHECK(fault.motion_share == Approx(1.0).epsilon(1e-12));
  CHECK(report.relative_motion ==
        Approx(static_cast<double>(broken.size()) * std::hypot(slip, opening)).epsilon(1e-12));
  CHECK(report.moved_bonds == report.broken_bonds);
}

TEST_CASE("A reverse fault's dip-slip is negative, an opening crack's has none", "[analysis]") {
  SECTION("reverse: the hanging wall moves up the dip") {
    RunResult result = triangular();
    const double top = top_z(result), c = std::cos(50 * kDegree), s = std::sin(50 * kDegree);
    cut_and_shift(result, [&](const Xyz& p) { return (p[0] - 30.0) * s + (p[2] - top) * c; },
                  {-1.5 * c, 0, 1.5 * s});
    const FaultReport report = analyze_faults(result);
    REQUIRE(report.faults.size() == 1);
    CHECK(report.faults[0].dip_slip == Approx(-1.5).margin(0.03));
    CHECK(report.faults[0].opening == Approx(0).margin(0.03));
  }
  SECTION("a vertical crack opening by 0.7 m") {
    RunResult result = triangular();
    cut_and_shift(result, [](const Xyz& p) { return p[0] - 30.25; }, {0.7, 0, 0});
    const FaultReport report = analyze_faults(result);
    REQUIRE(report.faults.size() == 1);
    const Fault& fault = report.faults[0];
    CHECK(fault.dip_direction == 0);
    // The fitted line is within a degree of the cut (the midpoints' staircase tilts it).
    const double tolerance = 0.7 * std::sin(kDipToleranceDeg * kDegree);
    CHECK(fault.opening == Approx(0.7).margin(tolerance));
    CHECK(fault.slip == Approx(0).margin(tolerance));
    CHECK(std::isnan(fault.dip_slip));  // no hanging wall on a vertical fault
    const std::string json = to_json(report);
    check_json_shape(json);
    CHECK(json.find("\"dip_slip_m\": null") != std::string::npos);
    const std::string text = to_text(report);
    CHECK(text.find("nan") == std::string::npos);  // "-" where there is no dip-slip
  }
}

TEST_CASE("The motion's shares, and min_offset keeps the bonds that moved", "[analysis]") {
  // Two vertical cracks: the one at x = 15.25 opens by 1 m, the one at x = 45.25 by 3 m.
  RunResult result = triangular();
  const auto first = cut_and_shift(result, [](const Xyz& p) { return p[0] - 15.25; }, {1, 0, 0});
  const auto second = cut_and_shift(result, [](const Xyz& p) { return p[0] - 45.25; }, {3, 0, 0});
  const double n1 = static_cast<double>(first.size()), n2 = static_cast<double>(second.size());

  const FaultReport all = analyze_faults(result);
  REQUIRE(all.faults.size() == 2);
  CHECK(all.broken_bonds == static_cast<std::int64_t>(first.size() + second.size()));
  CHECK(all.moved_bonds == all.broken_bonds);
  CHECK(all.relative_motion == Approx(n1 + 3 * n2).epsilon(1e-12));
  for (const Fault& fault : all.faults) {
    const bool is_second = fault.centroid[0] > 30;
    CHECK(fault.opening == Approx(is_second ? 3.0 : 1.0).epsilon(1e-3));  // the fit's tilt
    CHECK(fault.motion_share == Approx((is_second ? 3 * n2 : n1) / (n1 + 3 * n2)).epsilon(1e-12));
  }

  FaultOptions moving;
  moving.min_offset = 2.0;
  const FaultReport moved = analyze_faults(result, kLastSnapshot, moving);
  CHECK(moved.broken_bonds == all.broken_bonds);
  CHECK(moved.moved_bonds == static_cast<std::int64_t>(second.size()));
  CHECK(moved.min_offset == 2.0);
  CHECK(moved.relative_motion == Approx(3 * n2).epsilon(1e-12));
  REQUIRE(moved.faults.size() == 1);
  CHECK(moved.faults[0].centroid[0] == Approx(45.25).margin(0.5));
  CHECK(moved.faults[0].motion_share == Approx(1.0).epsilon(1e-12));
  CHECK(to_text(moved).find("moved by 2 m or more") != std::string::npos);
  check_json_with_python(to_json(moved));

  for (const double bad :
       {-1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    moving.min_offset = bad;
    CHECK_THROWS_AS(analyze_faults(result, kLastSnapshot, moving), InputError);
  }
}

TEST_CASE("In 3-D a fault's offsets split into opening, dip-slip and strike-slip", "[analysis]") {
  // A plane dipping 50 deg towards the azimuth 30 deg (from +x towards +y); its hanging
  // wall moves 2 m down the dip (the steepest descent in the plane), 1.5 m along the strike
  // and 0.3 m apart. Slip is the length of the in-plane part, dip-slip its down-dip part.
  const double dip = 50 * kDegree, azimuth = 30 * kDegree;
  const Xyz normal{std::sin(dip) * std::cos(azimuth), std::sin(dip) * std::sin(azimuth),
                   std::cos(dip)};
  const Xyz down{std::cos(dip) * std::cos(azimuth), std::cos(dip) * std::sin(azimuth),
                 -std::sin(dip)};
  const Xyz strike{-std::sin(azimuth), std::cos(azimuth), 0};
  Xyz shift;
  for (int c = 0; c < 3; ++c) shift[c] = 2.0 * down[c] + 1.5 * strike[c] + 0.3 * normal[c];
  RunResult result = cubic();
  const auto broken = cut_and_shift(
      result,
      [&](const Xyz& p) {
        return (p[0] - 7.3) * normal[0] + (p[1] - 7.6) * normal[1] + (p[2] - 7.4) * normal[2];
      },
      shift);
  const FaultReport report = analyze_faults(result);

  REQUIRE(report.faults.size() == 1);
  const Fault& fault = report.faults[0];
  CHECK(fault.bonds == static_cast<std::int64_t>(broken.size()));
  CHECK(std::abs(fault.dip_deg - 50) < kDipToleranceDeg);
  // Within |shift| sin(1 deg) for a plane fitted within a degree.
  const double tolerance = std::hypot(2.0, 1.5, 0.3) * std::sin(kDipToleranceDeg * kDegree);
  CHECK(fault.dip_slip == Approx(2.0).margin(tolerance));
  CHECK(fault.slip == Approx(2.5).margin(tolerance));
  CHECK(fault.opening == Approx(0.3).margin(tolerance));
  CHECK(fault.motion_share == Approx(1.0).epsilon(1e-12));
}
