// Tests of the problem-file reader: the Scene it builds and the message of every error.
#include "latfrac/io/problem_file.h"

#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "latfrac/base/error.h"
#include "latfrac/scene/scene.h"

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using latfrac::parse_problem;

namespace {

// Lines: name 1, [lattice] 2, dim 3, spacing 4, size 5, [material] 6, density 7, young 8,
// poisson 9.
const std::string minimal = R"(name = "t"
[lattice]
dim = 2
spacing = 500
size = [60e3, 30e3]
[material]
density = 2600
young = 100e9
poisson = 0.2
)";

const std::string full = R"(name = "graben-2d"
description = "the paper's Fig. 6"
[lattice]
dim = 2
spacing = 250
size = [60e3, 30e3]
[material]
density = 2600
young = 100e9
poisson = 0.2
[boundary]
z_max = "free"
x_min = "fixed"
[strength]
criterion = "elliptic"
sigma0 = 50e6
friction_angle = 34
tau0_factor = 3
[gravity]
[loading]
mode = "extension"
total = 0.04
[stepping]
method = "fixed"
increment = 1e-3
[[precut]]
from = [30e3, 30e3]
to = [30e3, 25e3]
[contact]
[[layer]]
z_min = 0
z_max = 10e3
young = 50e9
sigma0 = 80e6
[heterogeneity]
spread = 0.1
seed = 7
[large_kinematics]
enabled = false
[output]
snapshots = [0.01, 0.02, 0.04]
exaggeration = 5
[solver]
ordering = "amd"
max_iterations = 20
)";

// `text` with the first occurrence of `from` replaced by `to`.
std::string with(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

std::string error_of(const std::string& text, const std::vector<std::string>& overrides = {}) {
  try {
    parse_problem(text, "t.toml", overrides);
  } catch (const latfrac::InputError& error) {
    const std::string message = error.what();
    CHECK(message.find('\n') == std::string::npos);
    return message;
  }
  FAIL("no InputError for:\n" << text);
  return "";
}

}  // namespace

TEST_CASE("a full problem file resolves into the scene it describes", "[io]") {
  const latfrac::Scene scene = parse_problem(full, "full.toml");
  CHECK(scene.name == "graben-2d");
  CHECK(scene.description == "the paper's Fig. 6");
  CHECK(scene.lattice.dim == 2);
  CHECK(scene.lattice.spacing == 250);
  CHECK(scene.lattice.size == std::array<double, 3>{60e3, 0, 30e3});
  CHECK(scene.material.young == 100e9);
  CHECK(scene.faces[0] == latfrac::FaceCondition::fixed);
  CHECK(scene.faces[1] == latfrac::FaceCondition::extension);
  CHECK(scene.faces[4] == latfrac::FaceCondition::roller);
  REQUIRE(scene.strength);
  CHECK(scene.strength->criterion == latfrac::Criterion::elliptic);
  CHECK(scene.strength->sigma0 == 50e6);
  CHECK_FALSE(scene.strength->tau0);
  CHECK(scene.strength->friction_angle == 34);
  CHECK(scene.strength->tau0_factor == 3);
  REQUIRE(scene.gravity);
  CHECK(scene.gravity->g == 9.81);
  CHECK(scene.loading.total == 0.04);
  CHECK(scene.stepping.method == latfrac::SteppingMethod::fixed);
  CHECK(scene.stepping.increment == 1e-3);
  REQUIRE(scene.precuts.size() == 1);
  CHECK(scene.precuts[0].from == std::array<double, 3>{30e3, 0, 30e3});
  CHECK(scene.precuts[0].to == std::array<double, 3>{30e3, 0, 25e3});
  CHECK(scene.contact);
  REQUIRE(scene.layers.size() == 1);
  CHECK(scene.layers[0].z_max == 10e3);
  CHECK(scene.layers[0].material.young == 50e9);
  CHECK(scene.layers[0].material.density == 2600);
  CHECK(scene.layers[0].sigma0 == 80e6);
  CHECK_FALSE(scene.layers[0].tau0);
  REQUIRE(scene.heterogeneity);
  CHECK(scene.heterogeneity->spread == 0.1);
  CHECK(scene.heterogeneity->seed == 7);
  CHECK_FALSE(scene.large_kinematics);
  CHECK(scene.output.snapshots == std::vector<double>{0.01, 0.02, 0.04});
  CHECK(scene.output.exaggeration == 5);
  CHECK(scene.output.picture);
  CHECK(scene.solver.ordering == latfrac::Ordering::amd);
  CHECK(scene.solver.max_iterations == 20);
  CHECK(scene.solver.tolerance == 1e-10);
  CHECK(scene.source_path == "full.toml");
  CHECK(scene.source_text == full);
}

TEST_CASE("absent sections leave their effects off and defaults apply", "[io]") {
  const latfrac::Scene scene = parse_problem(minimal, "t.toml");
  CHECK_FALSE(scene.strength);
  CHECK_FALSE(scene.gravity);
  CHECK_FALSE(scene.contact);
  CHECK_FALSE(scene.heterogeneity);
  CHECK_FALSE(scene.large_kinematics);
  CHECK(scene.precuts.empty());
  CHECK(scene.layers.empty());
  CHECK(scene.loading.total == 0);
  CHECK(scene.stepping.method == latfrac::SteppingMethod::event);
  CHECK(scene.faces[0] == latfrac::FaceCondition::extension);
  CHECK(scene.faces[5] == latfrac::FaceCondition::free);
  CHECK(scene.output.snapshots.empty());
  CHECK(scene.solver.method == latfrac::EquilibriumMethod::newton);
  CHECK(scene.solver.relaxation_max_sweeps == 100000);

  const latfrac::Scene with_sections = parse_problem(
      minimal + "[contact]\nenabled = false\n[large_kinematics]\n[gravity]\ng = 0\n", "t.toml");
  CHECK_FALSE(with_sections.contact);
  CHECK(with_sections.large_kinematics);
  CHECK(with_sections.gravity->g == 0);
}

TEST_CASE("an unknown key or section names the closest valid one", "[io]") {
  CHECK(error_of(with(minimal, "spacing", "spaceing")) ==
        "t.toml:4: lattice.spaceing: unknown key (did you mean 'spacing'?); "
        "allowed in [lattice]: dim, kind, spacing, size, next_nearest, seed, mirror");
  CHECK_THAT(error_of(with(minimal, "young", "yng")), Contains("did you mean 'young'?"));
  CHECK_THAT(error_of(with(minimal, "spacing", "sp")), Contains("did you mean 'spacing'?"));
  CHECK_THAT(error_of(with(minimal, "density", "colour")),
             StartsWith("t.toml:7: material.colour: unknown key;") &&
                 Contains("allowed in [material]: density, young, poisson"));
  CHECK_THAT(error_of(minimal + "[gravty]\ng = 9.81\n"),
             StartsWith("t.toml:10: gravty: unknown section [gravty] (did you mean [gravity]?);"));
  CHECK_THAT(error_of(with(minimal, "[lattice]", "[latice]")),
             Contains("unknown section [latice] (did you mean [lattice]?)"));
}

TEST_CASE("a value of the wrong type says what was expected", "[io]") {
  CHECK(error_of(with(minimal, "spacing = 500", "spacing = \"500\"")) ==
        "t.toml:4: lattice.spacing: expected a number, got a string; allowed: spacing > 0 (m)");
  CHECK_THAT(error_of(with(minimal, "dim = 2", "dim = 2.5")),
             Contains("lattice.dim: expected an integer, got a floating-point number"));
  CHECK_THAT(
      error_of(minimal + "[contact]\nenabled = 1\n"),
      Contains("contact.enabled: expected a boolean, got an integer; allowed: true or false"));
  CHECK_THAT(error_of(minimal + "[strength]\ncriterion = 1\n"),
             Contains("expected a string, got an integer; allowed: \"tensile\", "
                      "\"tensile_or_shear\", \"elliptic\", \"drucker_prager\""));
  CHECK_THAT(error_of("precut = 1\n" + minimal),
             Contains("precut: expected an array of tables [[precut]], got an integer"));
}

TEST_CASE("integers are accepted where numbers are expected", "[io]") {
  CHECK(parse_problem(minimal, "t.toml").lattice.spacing == 500);
}

TEST_CASE("a missing required key or section is named at its table's line", "[io]") {
  CHECK(error_of(with(minimal, "young = 100e9\n", "")) ==
        "t.toml:6: material.young: missing required key; allowed: young > 0 (Pa)");
  CHECK_THAT(error_of(with(minimal, "name = \"t\"\n", "")), Contains("name: missing required key"));
  const std::string no_material = minimal.substr(0, minimal.find("[material]"));
  CHECK_THAT(error_of(no_material),
             StartsWith("t.toml:1: material: missing required section [material]; add it, "
                        "with keys density, young, poisson"));
}

TEST_CASE("a value out of range says what is allowed", "[io]") {
  CHECK(error_of(with(minimal, "spacing = 500", "spacing = -1")) ==
        "t.toml:4: lattice.spacing: -1 is out of range; allowed: spacing > 0 (m)");
  const std::string too_large = error_of(with(minimal, "poisson = 0.2", "poisson = 0.3"));
  CHECK_THAT(too_large, StartsWith("t.toml:9: material.poisson: 0.3 is too large"));
  CHECK_THAT(too_large, Contains("shear springs would be negative (ks < 0)") &&
                            Contains("at most 1/4") && Contains("-1 < poisson <= 0.25"));
  CHECK_THAT(error_of(with(minimal, "poisson = 0.2", "poisson = -1")),
             Contains("-1 is out of range; allowed: -1 < poisson <= 0.25"));
  CHECK_THAT(error_of(with(minimal, "dim = 2", "dim = 4")),
             Contains("lattice.dim: 4 is out of range"));
  CHECK_THAT(
      error_of(minimal + "[loading]\ntotal = 0.6\n"),
      Contains("loading.total: 0.6 is out of range; allowed: -0.5 <= total <= 0.5 (strain)"));
  CHECK_THAT(error_of(minimal + "[solver]\nrelaxation_omega = 2\n"),
             Contains("allowed: 0 < relaxation_omega < 2"));
  CHECK_THAT(error_of(minimal + "[boundary]\nx_min = \"rolle\"\n"),
             Contains("boundary.x_min: \"rolle\" is not allowed (did you mean \"roller\"?); "
                      "allowed: \"free\", \"roller\", \"fixed\", \"extension\""));
  CHECK_THAT(error_of(with(minimal, "\"t\"", "\"my run\"")),
             Contains("name: \"my run\" cannot name output files; allowed: letters, digits"));
}

TEST_CASE("contact.friction: a non-negative mu on an enabled contact", "[io]") {
  CHECK(parse_problem(minimal + "[contact]\nfriction = 0.6\n", "t.toml", {}).contact->friction ==
        0.6);
  CHECK(parse_problem(minimal + "[contact]\n", "t.toml", {}).contact->friction == 0);
  CHECK_THAT(error_of(minimal + "[contact]\nfriction = -0.1\n"),
             Contains("contact.friction: -0.1 is out of range"));
  CHECK_THAT(error_of(minimal + "[contact]\nfriction = nan\n"),
             Contains("contact.friction: must be finite"));
  CHECK_THAT(error_of(minimal + "[contact]\nenabled = false\nfriction = 0.6\n"),
             Contains("contact.friction: has no effect: contact.enabled is false"));
}

TEST_CASE("contact.friction_facets: 3 to 64 facets, in 3-D, with friction", "[io]") {
  const std::string three_d =
      with(with(minimal, "dim = 2", "dim = 3"), "size = [60e3, 30e3]", "size = [60e3, 10e3, 30e3]");
  CHECK(parse_problem(three_d + "[contact]\nfriction = 0.6\n", "t.toml", {})
            .contact->friction_facets == 8);
  CHECK(parse_problem(three_d + "[contact]\nfriction = 0.6\nfriction_facets = 16\n", "t.toml", {})
            .contact->friction_facets == 16);
  CHECK_THAT(error_of(three_d + "[contact]\nfriction = 0.6\nfriction_facets = 2\n"),
             Contains("contact.friction_facets: 2 is out of range"));
  CHECK_THAT(error_of(three_d + "[contact]\nfriction = 0.6\nfriction_facets = 65\n"),
             Contains("contact.friction_facets: 65 is out of range"));
  CHECK_THAT(error_of(three_d + "[contact]\nfriction_facets = 8\n"),
             Contains("contact.friction_facets: has no effect without friction"));
  CHECK_THAT(error_of(minimal + "[contact]\nfriction = 0.6\nfriction_facets = 8\n"),
             Contains("contact.friction_facets: has no effect in 2-D"));
}

TEST_CASE("contact.normal: along the bond (default) or across the crack", "[io]") {
  CHECK(parse_problem(minimal + "[contact]\n", "t.toml", {}).contact->normal ==
        latfrac::Contact::Normal::bond);
  CHECK(parse_problem(minimal + "[contact]\nnormal = \"crack\"\n", "t.toml", {}).contact->normal ==
        latfrac::Contact::Normal::crack);
  CHECK(parse_problem(minimal + "[contact]\nnormal = \"bond\"\n", "t.toml", {}).contact->normal ==
        latfrac::Contact::Normal::bond);
  CHECK_THAT(error_of(minimal + "[contact]\nnormal = \"plane\"\n"),
             Contains("contact.normal: ") && Contains("bond") && Contains("crack"));
  CHECK_THAT(error_of(minimal + "[contact]\nenabled = false\nnormal = \"crack\"\n"),
             Contains("contact.normal: has no effect: contact.enabled is false"));
}

TEST_CASE("nan and inf are rejected", "[io]") {
  CHECK(error_of(with(minimal, "spacing = 500", "spacing = nan")) ==
        "t.toml:4: lattice.spacing: must be finite, got nan; allowed: spacing > 0 (m)");
  CHECK_THAT(error_of(with(minimal, "30e3]", "inf]")),
             StartsWith("t.toml:5: lattice.size[1]: must be finite, got inf;"));
}

TEST_CASE("malformed TOML is reported at its line", "[io]") {
  // An unclosed array is reported where it opens, not where the parser noticed.
  const std::string message = error_of(with(minimal, "size = [60e3, 30e3]", "size = [60e3, 30e3"));
  CHECK_THAT(message, StartsWith("t.toml:5: malformed TOML: ") && Contains("not closed"));
  CHECK_THAT(error_of(with(minimal, "dim = 2\n", "dim = 2\ndim = 3\n")),
             StartsWith("t.toml:4: malformed TOML: ") && Contains("cannot redefine"));
}

TEST_CASE("a missing problem file is an input error naming the file", "[io]") {
  CHECK_THROWS_WITH(latfrac::read_problem_file("/nonexistent/x.toml"),
                    "cannot read problem file '/nonexistent/x.toml': No such file or directory");
}

TEST_CASE("a problem file is read from disk with its text", "[io]") {
  const auto path = std::filesystem::temp_directory_path() / "latfrac_problem_file_test.toml";
  std::ofstream(path) << minimal;
  const latfrac::Scene scene = latfrac::read_problem_file(path.string());
  std::filesystem::remove(path);
  CHECK(scene.source_path == path.string());
  CHECK(scene.source_text == minimal);
}

TEST_CASE("Overrides (--set) are applied and then validated", "[io]") {
  const latfrac::Scene scene =
      parse_problem(full, "t.toml",
                    {"lattice.spacing=500", "strength.criterion=tensile", "output.snapshots=[0.04]",
                     "description = \"overridden\""});
  CHECK(scene.lattice.spacing == 500);
  CHECK(scene.strength->criterion == latfrac::Criterion::tensile);
  CHECK(scene.output.snapshots == std::vector<double>{0.04});
  CHECK(scene.description == "overridden");
  CHECK(parse_problem(minimal, "t.toml", {"gravity.g=9.8"}).gravity->g == 9.8);

  CHECK(error_of(minimal, {"lattice.spacing=-1"}) ==
        "--set lattice.spacing: lattice.spacing: -1 is out of range; allowed: spacing > 0 (m)");
  CHECK(error_of(minimal, {"lattice.spaceing=3"}) ==
        "--set lattice.spaceing: lattice.spaceing: unknown key (did you mean 'spacing'?); "
        "allowed in [lattice]: dim, kind, spacing, size, next_nearest, seed, mirror");
  CHECK_THAT(error_of(minimal, {"latice.spacing=3"}),
             StartsWith("--set latice.spacing: latice: unknown section [latice] (did you mean "
                        "[lattice]?)"));
  CHECK_THAT(error_of(minimal, {"strength.criterion=tensile"}),
             StartsWith("--set strength.criterion: strength.sigma0: missing required key"));
  CHECK_THAT(error_of(minimal, {"lattice.spacing=abc"}),
             StartsWith("--set lattice.spacing: lattice.spacing: expected a number, got a string"));
  // An integer beyond 64 bits is a number TOML cannot hold, not a string.
  CHECK_THAT(error_of(minimal, {"lattice.seed=9223372036854775808"}),
             StartsWith("--set lattice.seed: 9223372036854775808 is not a number TOML can hold"));
}

TEST_CASE("a malformed --set override is an input error", "[io]") {
  CHECK_THAT(error_of(minimal, {"lattice.spacing"}),
             StartsWith("--set lattice.spacing: malformed override, it has no '='; expected "
                        "--set key.path=value"));
  CHECK_THAT(error_of(minimal, {"lattice..spacing=3"}), Contains("is not a key path"));
  CHECK_THAT(error_of(full, {"precut.0.from=[1, 2]"}),
             Contains("entries of an array of tables cannot be set from the command line"));
  CHECK_THAT(error_of(minimal, {"lattice.spacing.x=1"}),
             StartsWith("--set lattice.spacing.x: lattice.spacing: is a value, not a section"));
  // The override of the wrong path is named, not an earlier one beneath it.
  CHECK_THAT(error_of(minimal, {"lattice.spacing=3000", "lattice="}),
             StartsWith("--set lattice: lattice: expected a table"));
}

TEST_CASE("size has 2 numbers in 2-D and 3 in 3-D", "[io]") {
  CHECK_THAT(error_of(with(minimal, "[60e3, 30e3]", "[60e3, 10e3, 30e3]")),
             StartsWith("t.toml:5: lattice.size: expected an array of 2 numbers [Lx, Lz] "
                        "(lattice.dim = 2), got 3 numbers;"));
  CHECK_THAT(error_of(with(minimal, "dim = 2", "dim = 3")),
             Contains("expected an array of 3 numbers [Lx, Ly, Lz] (lattice.dim = 3), got 2"));
  const latfrac::Scene scene =
      parse_problem(with(with(minimal, "dim = 2", "dim = 3"), "[60e3,", "[60e3, 10e3,"), "t.toml");
  CHECK(scene.lattice.size == std::array<double, 3>{60e3, 10e3, 30e3});
  CHECK(scene.lattice.next_nearest);
  CHECK_THAT(error_of(with(minimal, "spacing = 500", "spacing = 20e3")),
             Contains("is less than 2 spacings"));
  CHECK_THAT(error_of(with(minimal, "dim = 2", "dim = 2\nnext_nearest = false")),
             Contains("lattice.next_nearest: only applies in 3-D"));
  CHECK_THAT(error_of(minimal + "[boundary]\ny_min = \"fixed\"\n"),
             Contains("boundary.y_min: a 2-D scene has no y faces"));
}

TEST_CASE("strength sections follow the criterion's rules", "[io]") {
  const std::string strength = minimal + "[strength]\n";
  CHECK(parse_problem(strength + "criterion = \"tensile\"\nsigma0 = 5e7\n", "t.toml")
            .strength->criterion == latfrac::Criterion::tensile);
  CHECK_THAT(error_of(strength + "criterion = \"elliptic\"\nsigma0 = 5e7\n"),
             StartsWith("t.toml:10: strength.tau0: missing required key; criterion \"elliptic\" "
                        "needs a shear strength"));
  CHECK_THAT(error_of(strength + "criterion = \"tensile_or_shear\"\nsigma0 = 5e7\n"),
             Contains("tau0: missing required key"));
  CHECK_THAT(error_of(strength + "criterion = \"drucker_prager\"\nsigma0 = 5e7\ntau0 = 1e7\n"),
             Contains("strength.friction_angle: missing required key; criterion "
                      "\"drucker_prager\" needs 0 <= friction_angle < 90 (degrees)"));
  CHECK_THAT(error_of(strength + "criterion = \"elliptic\"\nsigma0 = 5e7\ntau0 = 1e7\n"
                                 "tau0_factor = 3\n"),
             StartsWith("t.toml:14: strength.tau0_factor: cannot be combined with tau0"));
  CHECK_THAT(error_of(strength + "criterion = \"elliptic\"\nsigma0 = 5e7\nfriction_angle = 90\n"),
             Contains("allowed: 0 <= friction_angle < 90 (degrees)"));
  CHECK_THAT(error_of(strength + "sigma0 = 5e7\ntau0 = 1e7\n"),
             Contains("strength.criterion: missing required key"));
  CHECK(parse_problem(strength + "criterion = \"elliptic\"\nsigma0 = 5e7\ntau0 = 1e7\n"
                                 "tau0_factor = 1\n",
                      "t.toml")
            .strength->tau0 == 1e7);
}

TEST_CASE("cross-section checks: precuts, layers, stepping, snapshots", "[io]") {
  CHECK_THAT(error_of(with(full, "to = [30e3, 25e3]", "to = [70e3, 25e3]")),
             Contains("precut[0].to: point (70000, 25000) lies outside the box; allowed: "
                      "0 <= x <= 60000, 0 <= z <= 30000 (m)"));
  CHECK_THAT(error_of(with(full, "from = [30e3, 30e3]", "corner = [0, 0, 0]")),
             Contains("precut[0].corner: is a 3-D key"));
  CHECK_THAT(error_of(full + "[[layer]]\nz_min = 5e3\nz_max = 20e3\n"),
             Contains("layer[1].z_min: the layer from 5000 to 20000 m overlaps layer[0]"));
  CHECK_THAT(error_of(with(full, "z_max = 10e3", "z_max = 0")), Contains("layer[0].z_max"));
  CHECK_THAT(error_of(with(full, "increment = 1e-3", "")),
             Contains("stepping.increment: missing required key; method \"fixed\" needs"));
  CHECK_THAT(
      error_of(with(full, "[0.01, 0.02, 0.04]", "[0.01, 0.05]")),
      Contains(
          "output.snapshots[1]: 0.05 is out of range; allowed: 0 <= snapshots <= 0.04 (strain"));
  CHECK_THAT(error_of(with(full, "[0.01, 0.02, 0.04]", "[0.02, 0.01]")),
             Contains("output.snapshots: are not in loading order"));
  CHECK_THAT(error_of(minimal + "[heterogeneity]\nspread = 0.1\n"),
             Contains("has no effect: the scene has no [strength] section"));

  const std::string three_d = R"(name = "t3"
[lattice]
dim = 3
spacing = 1000
size = [30e3, 10e3, 15e3]
[material]
density = 2600
young = 100e9
poisson = 0.2
[[precut]]
corner = [15e3, 0, 10e3]
edge1 = [0, 10e3, 0]
edge2 = [0, 0, 5e3]
)";
  CHECK(parse_problem(three_d, "t.toml").precuts[0].edge2 == std::array<double, 3>{0, 0, 5e3});
  CHECK_THAT(error_of(with(three_d, "edge2 = [0, 0, 5e3]", "edge2 = [0, 20e3, 0]")),
             Contains("precut[0].edge2: is parallel to edge1"));
  CHECK_THAT(error_of(with(three_d, "edge2 = [0, 0, 5e3]", "edge2 = [0, 0, 9e3]")),
             Contains("corner + edge2 (15000, 0, 19000) lies outside the box"));
}

TEST_CASE("describe lists every section, with units and what is off", "[io]") {
  const std::string text = latfrac::describe(parse_problem(full, "full.toml"));
  for (const char* section : {"[lattice]", "[material]", "[boundary]", "[strength]", "[gravity]",
                              "[loading]", "[stepping]", "[[precut]]", "[contact]", "[[layer]]",
                              "[heterogeneity]", "[large_kinematics]", "[output]", "[solver]"}) {
    CHECK_THAT(text, Contains(section));
  }
  CHECK_THAT(text, Contains("250 m") && Contains("2600 kg/m^3") && Contains("1e+11 Pa"));
  CHECK_THAT(text, Contains("(derived"));
  CHECK_THAT(text, Contains("[large_kinematics]") && Contains("off"));

  const std::string elastic = latfrac::describe(parse_problem(minimal, "t.toml"));
  for (const char* section : {"[strength]", "[gravity]", "[[precut]]", "[contact]", "[[layer]]",
                              "[heterogeneity]", "[large_kinematics]"}) {
    CHECK_THAT(elastic, Contains(std::string(section) +
                                 std::string(26 - std::string(section).size(), ' ') + "off"));
  }
}

TEST_CASE("the example problems are valid", "[io]") {
  const auto problems = std::filesystem::path(__FILE__).parent_path().parent_path() / "problems";
  for (const char* name : {"lithostatic-2d.toml", "lithostatic-3d.toml"}) {
    const latfrac::Scene scene = latfrac::read_problem_file((problems / name).string());
    CHECK(scene.gravity);
    CHECK(scene.material.poisson == 0.2);
    CHECK(scene.loading.total == 0);
  }
}

TEST_CASE("[lattice] kind and seed: random lattices, their keys and their range of nu", "[io]") {
  const std::string random =
      with(minimal, "spacing = 500", "kind = \"random\"\nseed = 42\nspacing = 500");
  const latfrac::Scene scene = parse_problem(random, "t.toml");
  CHECK(scene.lattice.kind == latfrac::LatticeKind::random);
  CHECK(scene.lattice.seed == 42);
  CHECK(parse_problem(minimal, "t.toml").lattice.kind == latfrac::LatticeKind::regular);
  CHECK(parse_problem(with(minimal, "spacing = 500", "kind = \"triangular\"\nspacing = 500"),
                      "t.toml")
            .lattice.kind == latfrac::LatticeKind::regular);
  // A random 2-D lattice reaches nu = 0.3 (up to 0.326); a regular one stops at 1/4.
  CHECK(parse_problem(with(random, "poisson = 0.2", "poisson = 0.3"), "t.toml").material.poisson ==
        0.3);
  CHECK_THAT(error_of(with(random, "poisson = 0.2", "poisson = 0.33")),
             Contains("material.poisson: 0.33 is too large: a random 2-D lattice reaches nu = 0.3257"));
  CHECK_THAT(error_of(with(random, "poisson = 0.2", "poisson = -0.1")),
             Contains("material.poisson: -0.1 is too small"));
  CHECK_THAT(error_of(with(minimal, "spacing = 500", "kind = \"hcp\"\nspacing = 500")),
             Contains("lattice.kind: \"hcp\" is a 3-D lattice"));
  CHECK_THAT(error_of(with(minimal, "spacing = 500", "seed = 3\nspacing = 500")),
             Contains("lattice.seed: only applies to a random lattice"));
  CHECK_THAT(error_of(with(minimal, "spacing = 500", "kind = \"voronoi\"\nspacing = 500")),
             Contains("lattice.kind"));
  CHECK_THAT(error_of(with(random, "seed = 42", "seed = -1")), Contains("lattice.seed"));
  CHECK_THAT(error_of(with(minimal, "spacing = 500", "mirror = true\nspacing = 500")),
             Contains("lattice.mirror: only applies to a random lattice"));
  CHECK(parse_problem(with(random, "seed = 42", "seed = 42\nmirror = true"), "t.toml").lattice.mirror);
  CHECK_THAT(error_of(with(random, "seed = 42", "seed = 42\nmirror = 1")), Contains("lattice.mirror"));
}

TEST_CASE("[gravity] initial_stress: lithostatic on random lattices with small kinematics only",
          "[io][initial_stress]") {
  const std::string random =
      with(minimal, "spacing = 500", "kind = \"random\"\nseed = 42\nspacing = 500");
  CHECK_FALSE(parse_problem(minimal + "[gravity]\n", "t.toml").gravity->lithostatic);
  CHECK(parse_problem(random + "[gravity]\ninitial_stress = \"lithostatic\"\n", "t.toml")
            .gravity->lithostatic);
  CHECK_THAT(error_of(minimal + "[gravity]\ninitial_stress = \"lithostatic\"\n"),
             Contains("gravity.initial_stress: \"lithostatic\" on a triangular lattice"));
  CHECK_THAT(error_of(random + "[gravity]\ninitial_stress = \"lithostatic\"\n[large_kinematics]\n"),
             Contains("large_kinematics.enabled: large kinematics with gravity.initial_stress"));
  CHECK_THAT(error_of(random + "[gravity]\ninitial_stress = \"k0\"\n"),
             Contains("gravity.initial_stress"));
  // stress_ratio K: 1 unless given, read with the lithostatic start, refused without it.
  CHECK(parse_problem(random + "[gravity]\ninitial_stress = \"lithostatic\"\n", "t.toml")
            .gravity->stress_ratio == 1);
  CHECK(parse_problem(random + "[gravity]\ninitial_stress = \"lithostatic\"\nstress_ratio = 0.4\n",
                      "t.toml")
            .gravity->stress_ratio == 0.4);
  CHECK_THAT(error_of(random + "[gravity]\nstress_ratio = 0.4\n"),
             Contains("gravity.stress_ratio: has no effect"));
  CHECK_THAT(error_of(random + "[gravity]\ninitial_stress = \"lithostatic\"\nstress_ratio = -1\n"),
             Contains("gravity.stress_ratio"));
  // overburden p0 (Pa): 0 unless given, read with the lithostatic start, refused without it.
  CHECK(parse_problem(random + "[gravity]\ninitial_stress = \"lithostatic\"\n", "t.toml")
            .gravity->overburden == 0);
  CHECK(parse_problem(random + "[gravity]\ninitial_stress = \"lithostatic\"\noverburden = 2e8\n",
                      "t.toml")
            .gravity->overburden == 2e8);
  CHECK_THAT(error_of(random + "[gravity]\noverburden = 2e8\n"),
             Contains("gravity.overburden: needs the lithostatic start"));
  CHECK_THAT(error_of(random + "[gravity]\ninitial_stress = \"lithostatic\"\noverburden = -1\n"),
             Contains("gravity.overburden"));
}

TEST_CASE("every scene says which of the two models it runs", "[io]") {
  // docs/model.md, "Two models": the paper's model, or the complete model's options
  // (random lattice, internal friction, contact friction, basal discontinuity, and layers
  // and heterogeneity beyond them).
  const std::string problems = LATFRAC_PROBLEMS_DIR;
  auto label = [&](const std::string& name, const std::vector<std::string>& overrides = {}) {
    return latfrac::model_label(latfrac::read_problem_file(problems + "/" + name, overrides));
  };
  for (const char* name : {"fig4a-tensile-2d.toml", "fig4b-tensile-or-shear-2d.toml",
                           "fig6-elliptic-graben-2d.toml", "fig7c-drucker-prager-2d.toml",
                           "reference-3d.toml", "lithostatic-2d.toml"})
    CHECK(label(name) == "the paper's model");
  const std::string complete =
      "the complete model: random lattice, internal friction, contact friction, basal discontinuity";
  CHECK(label("graben-complete-2d.toml") == complete);
  CHECK(label("graben-complete-3d.toml") == complete);
  CHECK(label("graben-complete-2d.toml", {"contact.friction=0", "strength.internal_friction=0"}) ==
        "the paper's model with: random lattice, basal discontinuity");
  CHECK(label("fig6-elliptic-graben-random-2d.toml") == "the paper's model with: random lattice");
  CHECK(label("fig6-elliptic-graben-2d.toml", {"contact.friction=0.6"}) ==
        "the paper's model with: contact friction");
  CHECK(label("fig6-elliptic-graben-2d.toml", {"heterogeneity.spread=0.2"}) ==
        "the paper's model with: heterogeneity");
  CHECK(label("fig6-elliptic-graben-2d.toml", {"heterogeneity.spread=0"}) == "the paper's model");
  CHECK(label("graben-complete-2d.toml",
              {"layer=[{z_min=0, z_max=6e3, young=10e9}]"}) == complete + ", layers");
}
