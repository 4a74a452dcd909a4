// Contacts along cracks (contact.normal = "crack"; docs/model.md, section 8): the plane
// a failure picks against Coulomb's construction by hand, and a wedge between two
// inclined pre-cuts that must slide down by the kinematics of its two faults.
#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "hard_case_checks.h"
#include "latfrac/criteria/crack_plane.h"
#include "latfrac/io/problem_file.h"
#include "latfrac/scene/model_builder.h"
#include "latfrac/scene/run.h"

using namespace latfrac;
using namespace latfrac::testing;

namespace {

constexpr double deg = std::numbers::pi / 180;

// A stress matrix in Voigt order xx, yy, zz, yz, xz, xy.
VoigtStress voigt(const Mat3& m) { return {m(0, 0), m(1, 1), m(2, 2), m(1, 2), m(0, 2), m(0, 1)}; }

VoigtStress principal(const Mat3& rotation, double s1, double s2, double s3) {
  return voigt(rotation * Vec3(s1, s2, s3).asDiagonal() * rotation.transpose());
}

}  // namespace

TEST_CASE("Crack plane: a shear failure's normal lies at 45 + phi/2 from sigma1, nearer the bond",
          "[crack]") {
  // 2-D, sigma1 vertical (-100 MPa), sigma3 horizontal (-40): Coulomb's planes dip
  // 45 + phi/2 = 60 deg for phi = 30, their normals (+-sin 60, 0, cos 60).
  const VoigtStress stress = {-40e6, 0, -100e6, 0, 0, 0};
  const double phi = 30 * deg;
  const Vec3 bond = Vec3(0.8, 0, 0.6);  // nearer the plane dipping to -x (normal +x, +z)
  const Vec3 n = crack_plane_normal(stress, bond, BreakMode::shear, phi, 2);
  CHECK(n.x() == Approx(std::sin(60 * deg)).margin(1e-12));
  CHECK(n.y() == 0);
  CHECK(n.z() == Approx(std::cos(60 * deg)).margin(1e-12));
  // The other bond picks the conjugate plane, oriented along the bond.
  const Vec3 other = crack_plane_normal(stress, Vec3(-0.8, 0, 0.6), BreakMode::shear, phi, 2);
  CHECK(other.x() == Approx(-std::sin(60 * deg)).margin(1e-12));
  CHECK(other.z() == Approx(std::cos(60 * deg)).margin(1e-12));
  const Vec3 down = crack_plane_normal(stress, Vec3(0.8, 0, -0.6), BreakMode::shear, phi, 2);
  CHECK(down.x() == Approx(std::sin(60 * deg)).margin(1e-12));
  CHECK(down.z() == Approx(-std::cos(60 * deg)).margin(1e-12));
  // phi = 0: Tresca's planes at 45 deg.
  const Vec3 tresca = crack_plane_normal(stress, bond, BreakMode::shear, 0, 2);
  CHECK(tresca.x() == Approx(std::sqrt(0.5)).margin(1e-12));
  CHECK(tresca.z() == Approx(std::sqrt(0.5)).margin(1e-12));
  // A tensile failure: the plane perpendicular to sigma3 (a vertical crack), whatever phi.
  const Vec3 t = crack_plane_normal(stress, bond, BreakMode::tensile, phi, 2);
  CHECK(t.x() == Approx(1).margin(1e-12));
  CHECK(t.z() == Approx(0).margin(1e-12));
  // The y components of a 2-D stress (the out-of-plane stress) are not read.
  VoigtStress with_y = stress;
  with_y[1] = -500e6;
  CHECK((crack_plane_normal(with_y, bond, BreakMode::shear, phi, 2) - n).norm() < 1e-12);
  // No deviatoric stress: no plane is preferred, and the bond's own facet is kept.
  const VoigtStress isotropic = voigt(-50e6 * Mat3::Identity());
  CHECK(crack_plane_normal(isotropic, bond, BreakMode::shear, phi, 2) == bond);
  CHECK(crack_plane_normal(isotropic, Vec3(0, 1, 0), BreakMode::shear, phi, 3) == Vec3(0, 1, 0));
}

TEST_CASE("Crack plane in 3-D: rotating the stress and the bond rotates the normal", "[crack]") {
  // sigma1 along x, sigma2 along y, sigma3 along z: the normal lies in the x-z plane at
  // 45 + phi/2 from x. Any rotation of stress and bond rotates it alike.
  const double phi = 35 * deg, beta = 45 * deg + phi / 2;
  const Vec3 bond = Vec3(0.3, 0.5, 0.81).normalized();
  const Vec3 expected = Vec3(std::cos(beta), 0, std::sin(beta));  // nearer the bond than (c, 0, -s)
  const VoigtStress stress = principal(Mat3::Identity(), -300e6, -200e6, -120e6);
  const Vec3 n = crack_plane_normal(stress, bond, BreakMode::shear, phi, 3);
  CHECK((n - expected).norm() < 1e-12);
  const Vec3 t = crack_plane_normal(stress, bond, BreakMode::tensile, phi, 3);
  CHECK((t - Vec3(0, 0, 1)).norm() < 1e-12);
  for (const Vec3 axis : {Vec3(1, 2, 3), Vec3(-1, 0.2, 0.1), Vec3(0, 0, 1)}) {
    for (const double angle : {0.3, 1.7, -2.4}) {
      const Mat3 r = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
      const VoigtStress rotated = principal(r, -300e6, -200e6, -120e6);
      const Vec3 m = crack_plane_normal(rotated, r * bond, BreakMode::shear, phi, 3);
      CHECK((m - r * expected).norm() < 1e-9);
      CHECK(std::abs(m.norm() - 1) < 1e-12);
      CHECK(m.dot(r * bond) > 0);
    }
  }
}

namespace {

// The complete 2-D scene at 1000 m made unbreakable, with two pre-cuts dipping 60 deg: a
// master fault from the basal discontinuity (30 km) up to the surface, dipping to +x, and
// an antithetic one from the master at 15 km depth up to the surface, dipping to -x. As
// the base's halves move apart, the wedge between the faults can only follow them by
// sliding down the master fault, by the separation g of the two sides: down by g sin 60,
// towards +x by g cos 60 (relative to the footwall; contact friction 0.6 < tan 60).
struct WedgeMotion {
  double separation = 0;              // mean ux of the right block less the footwall's, m
  double wedge_dx = 0, wedge_dz = 0;  // the wedge's mean motion less the footwall's, m
};

WedgeMotion wedge_motion(const std::string& normal) {
  const double c = 1 / std::tan(60 * deg), xd = 30e3, zi = 15e3, xi = xd - zi * c;
  const auto point = [](double x, double z) {
    return "[" + std::to_string(x) + "," + std::to_string(z) + "]";
  };
  const std::string cuts = "precut=[{from=" + point(xd + 500 * c, -500) +
                           ",to=" + point(xd - 31e3 * c, 31e3) +
                           "},{from=" + point(xi - 300 * c, zi - 300) +
                           ",to=" + point(xi + (31e3 - zi) * c, 31e3) + "}]";
  const Scene scene =
      read_problem_file(std::string(LATFRAC_PROBLEMS_DIR) + "/graben-complete-2d.toml",
                        {"strength.sigma0=1e13", "loading.total=0.01",
                         "output.snapshots=[0.0,0.01]", "contact.normal=\"" + normal + "\"", cuts});
  const RunResult result = run_scene(scene, quiet());
  REQUIRE(result.summary.complete);
  for (const BreakEvent& event : result.events)  // nothing breaks: only the cuts move
    REQUIRE(event.mode == BreakMode::precut);
  const Snapshot &start = result.snapshots.front(), &end = result.snapshots.back();
  double sum[3][3] = {};  // footwall, wedge, right block: count, dx, dz
  for (std::size_t k = 0; k < result.node_count(); ++k) {
    const double x = result.positions[3 * k], z = result.positions[3 * k + 2];
    // Signed distances to the master fault (> 0 above it) and the antithetic (> 0 right).
    const double above = (z - (xd - x) / c) * std::cos(60 * deg);
    const double right = (x - (xi + (z - zi) * c)) * std::sin(60 * deg);
    if (std::abs(above) < 1000 || (z > zi - 1000 && std::abs(right) < 1000)) continue;
    const int part = above < 0 ? 0 : (z > zi && right < 0 ? 1 : 2);
    sum[part][0] += 1;
    sum[part][1] += end.displacement[3 * k] - start.displacement[3 * k];
    sum[part][2] += end.displacement[3 * k + 2] - start.displacement[3 * k + 2];
  }
  for (auto& part : sum) REQUIRE(part[0] > 50);
  const auto mean = [&](int part, int axis) { return sum[part][axis] / sum[part][0]; };
  return {mean(2, 1) - mean(0, 1), mean(1, 1) - mean(0, 1), mean(1, 2) - mean(0, 2)};
}

}  // namespace

TEST_CASE(
    "Contacts along cracks: a wedge between inclined pre-cuts on a random lattice slides as "
    "its faults' kinematics say, and contacts along the bonds lock it",
    "[crack]") {
  const WedgeMotion crack = wedge_motion("crack");
  const double g = crack.separation;
  CHECK(g == Approx(600).epsilon(0.05));  // lambda 0.01 of 60 km, less the blocks' strain
  CHECK(crack.wedge_dz == Approx(-g * std::sin(60 * deg)).epsilon(0.03));
  CHECK(crack.wedge_dx == Approx(g * std::cos(60 * deg)).epsilon(0.05));
  // The paper's contacts act along the broken bonds, whose directions scatter about the
  // cut's normal: sliding along the cut would press some of them together, so the wedge
  // stays on the footwall (docs/validation.md, "Why a rift: contacts that lock").
  const WedgeMotion bond = wedge_motion("bond");
  CHECK(std::abs(bond.wedge_dz) < 0.1 * g);
}

TEST_CASE(
    "Contacts along cracks: a pre-cut's bonds take its plane's normal, the rest their own "
    "direction until they break",
    "[crack]") {
  // 3-D: an inclined rectangle, normal edge1 x edge2 by hand; 2-D: a segment dipping 60 deg.
  const Scene three = read_problem_file(
      std::string(LATFRAC_PROBLEMS_DIR) + "/graben-complete-3d.toml",
      {"lattice.spacing=5000", "contact.normal=\"crack\"",
       "precut=[{corner=[20e3,-1e3,2e3],edge1=[0.0,12e3,0.0],edge2=[10e3,0.0,17.32e3]}]"});
  const Scene two =
      read_problem_file(std::string(LATFRAC_PROBLEMS_DIR) + "/graben-complete-2d.toml",
                        {"lattice.spacing=2000", "contact.normal=\"crack\"",
                         "precut=[{from=[30300.0,-500.0],to=[12400.0,30500.0]}]"});
  // edge1 x edge2 = (12e3 * 17.32e3, 0, -12e3 * 10e3), normalized; the segment's normal
  // (its direction (-17.9e3, 31e3) turned a quarter).
  const Vec3 n3 = Vec3(17.32e3, 0, -10e3).normalized();
  const Vec3 n2 = Vec3(31e3, 0, 17.9e3).normalized();
  for (const auto& [scene, normal] : {std::pair{&three, n3}, std::pair{&two, n2}}) {
    const Model model = build_model(*scene);
    REQUIRE(model.contacts_along_cracks());
    std::size_t cut = 0;
    for (std::int64_t b = 0; b < model.lattice.bond_count(); ++b) {
      const Vec3& n0 = model.lattice.bond_direction[b];
      const Vec3& n = model.contact_direction(b);
      if (!model.precut[b]) {
        CHECK(n == n0);
        continue;
      }
      ++cut;
      CHECK(std::abs(std::abs(n.dot(normal)) - 1) < 1e-12);
      CHECK(n.dot(n0) > 0);
      CHECK(model.springs(b).direction == n);  // a cut bond is broken: its contact's springs
    }
    CHECK(cut > 10);
  }
  // Contacts along the bonds (the default): every contact acts along its bond.
  const Model plain = build_model(read_problem_file(
      std::string(LATFRAC_PROBLEMS_DIR) + "/graben-complete-2d.toml", {"lattice.spacing=2000"}));
  CHECK_FALSE(plain.contacts_along_cracks());
  for (std::int64_t b = 0; b < plain.lattice.bond_count(); ++b)
    CHECK(plain.contact_direction(b) == plain.lattice.bond_direction[b]);
}
