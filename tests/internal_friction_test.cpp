// Pressure-dependent shear strength ([strength] internal_friction = mu_i): the shear
// strength tau0 + mu_i <-sigma_n>+ in the indices, on the critical plane (Mohr-Coulomb) and
// in the closed-form crossings, against hand values, brute force over planes and sampling,
// and a lattice's first break at the hand-computed lambda for each criterion and reading.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "criterion_calls.h"
#include "latfrac/base/error.h"
#include "latfrac/criteria/crossing.h"
#include "latfrac/scene/run.h"
#include "sampling.h"
#include "scenes.h"

using namespace latfrac;
using namespace latfrac::testing;

namespace {

constexpr double MPa = 1e6;
constexpr double inf = std::numeric_limits<double>::infinity();

// The Mohr-Coulomb shear part by brute force: the largest (tau + mu sigma_n) / tau0 over
// sampled planes.
double sampled_coulomb(const VoigtStress& stress, int dim, double tau0, double mu) {
  double best = -inf;
  for_each_sampled_plane(dim, [&](const Eigen::Vector3d& n) {
    const ResolvedStress r = resolve_on(stress, n);
    best = std::max(best, (r.shear.norm() + mu * r.normal) / tau0);
  });
  return best;
}

}  // namespace

TEST_CASE("internal friction raises the shear strength in compression only", "[criterion][friction]") {
  const double sigma0 = 50 * MPa, tau0 = 20 * MPa, mu = 0.6;
  // sigma_n = -10 MPa: strength 20 + 0.6 * 10 = 26 MPa.
  const FailureIndex either =
      failure_index(Criterion::tensile_or_shear, -10 * MPa, 30 * MPa, sigma0, tau0, mu);
  CHECK(either.value == Approx(30.0 / 26.0).epsilon(1e-14));
  CHECK(either.mode == BreakMode::shear);
  CHECK(failure_index(Criterion::elliptic, -10 * MPa, 30 * MPa, sigma0, tau0, mu).value ==
        Approx(std::pow(30.0 / 26.0, 2)).epsilon(1e-14));
  // In tension the strength is tau0: (10/50)^2 + (30/20)^2, and 30/20 for the maximum.
  CHECK(failure_index(Criterion::elliptic, 10 * MPa, 30 * MPa, sigma0, tau0, mu).value ==
        Approx(0.04 + 2.25).epsilon(1e-14));
  CHECK(failure_index(Criterion::tensile_or_shear, 10 * MPa, 30 * MPa, sigma0, tau0, mu).value ==
        Approx(1.5).epsilon(1e-14));
  // mu = 0 is the criterion without it.
  CHECK(failure_index(Criterion::tensile_or_shear, -10 * MPa, 30 * MPa, sigma0, tau0, 0).value ==
        Approx(1.5).epsilon(1e-14));
}

TEST_CASE("internal friction: bad values and unsupported combinations are refused", "[criterion][friction]") {
  Strength s;
  s.criterion = Criterion::tensile_or_shear;
  s.sigma0 = 50 * MPa;
  s.tau0 = 20 * MPa;
  for (double bad : {-0.1, std::numeric_limits<double>::quiet_NaN(), inf}) {
    s.internal_friction = bad;
    CHECK_THROWS_AS(resolve_criterion(s, 2), InputError);
  }
  s.internal_friction = 0.6;
  CHECK(resolve_criterion(s, 2).internal_friction == 0.6);
  s.criterion = Criterion::tensile;
  CHECK_THROWS_AS(resolve_criterion(s, 2), InputError);
  s.criterion = Criterion::drucker_prager;
  s.friction_angle = 30;
  CHECK_THROWS_AS(resolve_criterion(s, 2), InputError);
  s.criterion = Criterion::elliptic;
  s.bond_stress = BondStress::critical_plane;
  CHECK_THROWS_AS(resolve_criterion(s, 2), InputError);
}

TEST_CASE("on the critical plane internal friction is Mohr-Coulomb", "[criterion][friction]") {
  const double sigma0 = 50 * MPa, tau0 = 20 * MPa, mu = 0.6;
  // xx = -100, zz = -20 MPa: c = -60, r = 40; the circle touches the line
  // tau = tau0' - mu sigma_n where tau0' = r sqrt(1 + mu^2) + mu c.
  const VoigtStress compressed{-100 * MPa, -60 * MPa, -20 * MPa, 0, 0, 0};
  const double touching = 40 * MPa * std::sqrt(1 + mu * mu) - mu * 60 * MPa;
  for (int dim : {2, 3}) {
    const FailureIndex f =
        critical_plane_index(Criterion::tensile_or_shear, compressed, dim, sigma0, touching, mu);
    CHECK(f.value == Approx(1).epsilon(1e-14));
    CHECK(f.mode == BreakMode::shear);
  }
  // Random states: the shear part is the largest (tau + mu sigma_n) / tau0 over the planes.
  std::mt19937_64 rng(15);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (int trial = 0; trial < 24; ++trial) {
    VoigtStress s;
    for (int i = 0; i < 6; ++i) s[i] = 60 * MPa * unit(rng) - (i < 3 ? 60 * MPa : 0);
    const int dim = 2 + trial % 2;
    if (dim == 2) s[3] = s[5] = 0;
    // The index is never below 0 (a state far inside the strength has f = 0).
    const double shear_part = std::max(sampled_coulomb(s, dim, tau0, mu), 0.0);
    const double exact =
        critical_plane_index(Criterion::tensile_or_shear, s, dim, 1e30, tau0, mu).value;
    INFO("trial " << trial);
    CHECK(exact >= shear_part - 1e-12 * std::abs(shear_part));
    CHECK(exact == Approx(shear_part).epsilon(2e-4).margin(1e-12));
  }
}

TEST_CASE("crossings with internal friction: a hand-solved path and random paths", "[crossing][friction]") {
  const double sigma0 = 50 * MPa, tau0 = 20 * MPa;
  // sigma_n = -20 + l, |t| = 2 l (MPa), mu = 0.5: 2 l = 20 + 0.5 (20 - l) at l = 12, where
  // sigma_n = -8 is still compressive. Without friction: 2 l = 20 at l = 10.
  AffineBondStress s;
  s.normal0 = -20 * MPa;
  s.normal1 = 1 * MPa;
  s.shear0 = Eigen::Vector3d::Zero();
  s.shear1 = Eigen::Vector3d(2 * MPa, 0, 0);
  for (Criterion c : {Criterion::tensile_or_shear, Criterion::elliptic}) {
    CHECK(first_crossing(c, s, sigma0, tau0, 0, 100, 0.5) == Approx(12).epsilon(1e-13));
    CHECK(first_crossing(c, s, sigma0, tau0, 0, 100, 0) == Approx(10).epsilon(1e-13));
  }
  // A path that turns from compression into tension before it fails: sigma_n = -5 + l,
  // |t| = 3 l, mu = 0.5: in compression 3 l = 20 + 0.5 (5 - l) needs l = 6.43 > 5, so it
  // crosses in tension where tensile_or_shear's shear part is 3 l / 20 = 1 at l = 20/3.
  s.normal0 = -5 * MPa;
  s.shear1 = Eigen::Vector3d(0, 0, 3 * MPa);
  CHECK(first_crossing(Criterion::tensile_or_shear, s, 1e30, tau0, 0, 100, 0.5) ==
        Approx(20.0 / 3).epsilon(1e-13));

  // Random affine paths against sampling of the index.
  std::mt19937_64 rng(2015);
  std::uniform_real_distribution<double> unit(-1, 1), positive(0, 1);
  for (Criterion c : {Criterion::tensile_or_shear, Criterion::elliptic}) {
    int at_from = 0, crossing = 0, none = 0;
    for (int trial = 0; trial < 1500; ++trial) {
      const double mu = 0.2 + positive(rng);
      AffineBondStress p;
      p.normal0 = 1.5 * sigma0 * unit(rng) - 20 * MPa;
      p.normal1 = 3 * sigma0 * unit(rng);
      p.shear0 = 40 * MPa * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
      p.shear1 = 80 * MPa * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
      if (trial % 3 == 0) p.shear0.y() = p.shear1.y() = 0;
      const double from = unit(rng), to = from + 2 * positive(rng);
      const auto f = [&](double l) {
        return failure_index(c, p.normal0 + l * p.normal1, (p.shear0 + l * p.shear1).norm(),
                             sigma0, tau0, mu)
            .value;
      };
      const double exact = first_crossing(c, p, sigma0, tau0, from, to, mu);
      const double sampled = sampled_crossing(f, from, to, 4000);
      INFO("criterion " << static_cast<int>(c) << " trial " << trial);
      if (sampled == inf) {
        CHECK(exact == inf);
        ++none;
        continue;
      }
      (sampled == from ? at_from : crossing)++;
      CHECK(exact == Approx(sampled).margin(1e-10 * std::max(std::abs(sampled), to - from)));
    }
    CHECK(at_from > 50);
    CHECK(crossing > 200);
    CHECK(none > 50);
  }
}

TEST_CASE("internal friction: the first break of a lattice in uniaxial-strain compression",
          "[continuation][friction]") {
  // Rollers on top and base, compression lambda < 0: eps_xx = lambda, eps_zz = 0
  // everywhere, so the 60 and 120 degree bonds (c = cos 60, s = sin 60) are compressed and
  // sheared; the horizontal ones are only compressed, the vertical ones do not exist.
  const double tau0 = 5 * MPa, mu = 0.2, c = 0.5, s = std::sqrt(3.0) / 2;
  Scene scene = testing::box_scene(2, 1.0, {20.0, 0, 10.0}, false);
  scene.faces[static_cast<int>(Face::z_max)] = FaceCondition::roller;
  scene.strength = testing::strength_of(Criterion::tensile_or_shear, 50 * MPa);
  scene.strength->criterion = GENERATE(Criterion::tensile_or_shear, Criterion::elliptic);
  scene.strength->tau0 = tau0;
  scene.strength->friction_angle.reset();
  scene.strength->internal_friction = mu;
  scene.strength->bond_stress =
      GENERATE(BondStress::strain, BondStress::tensor, BondStress::critical_plane);
  if (scene.strength->criterion == Criterion::elliptic &&
      scene.strength->bond_stress == BondStress::critical_plane)
    return;  // refused (docs/criteria.md)
  scene.stepping = {SteppingMethod::event, 0};
  scene.loading.total = -5e-3;
  const Model model = build_model(scene);
  double expected = 0;
  const double E = scene.material.young, nu = scene.material.poisson;
  const double lame = E * nu / ((1 + nu) * (1 - 2 * nu)), shear_modulus = E / (2 * (1 + nu));
  switch (scene.strength->bond_stress) {
    case BondStress::strain: {
      // The bond's own strain: sigma_n = E_b eps c^2, tau = G_b |eps| c s.
      std::int64_t b = 0;
      while (std::abs(model.lattice.bond_direction[b].z()) < 0.1) ++b;
      const double Eb = model.bond_young[b], Gb = model.bond_shear_modulus[b];
      expected = tau0 / (Gb * c * s - mu * Eb * c * c);
      break;
    }
    case BondStress::tensor:
      // Resolved tensor: sigma_xx = (lame + 2 G) eps, sigma_zz = lame eps,
      // sigma_n = sigma_xx c^2 + sigma_zz s^2, tau = 2 G |eps| c s.
      expected = tau0 / (2 * shear_modulus * c * s -
                         mu * ((lame + 2 * shear_modulus) * c * c + lame * s * s));
      break;
    case BondStress::critical_plane:
      // Mohr-Coulomb: centre (lame + G) eps, radius G |eps|.
      expected = tau0 / (shear_modulus * std::sqrt(1 + mu * mu) - mu * (lame + shear_modulus));
      break;
  }
  REQUIRE(expected > 0);
  REQUIRE(expected < 5e-3);
  // Node stresses on the faces are not the interior's (node_stress.h): bonds with a node
  // on a face get 100 times the strength, so an interior bond breaks first.
  const auto first_break = [&](const Scene& sc) {
    Model m = build_model(sc);
    for (std::int64_t b = 0; b < m.lattice.bond_count(); ++b) {
      const Bond& bond = m.lattice.bonds[b];
      if (m.lattice.face_mask[bond.i] || m.lattice.face_mask[bond.j]) {
        m.bond_sigma0[b] *= 100;
        m.bond_tau0[b] *= 100;
      }
    }
    const RunResult result = testing::run_model(m, sc);
    REQUIRE(!result.events.empty());
    return result.events.front();
  };
  const BreakEvent first = first_break(scene);
  INFO("criterion " << static_cast<int>(scene.strength->criterion) << " reading "
                    << static_cast<int>(scene.strength->bond_stress));
  CHECK(-first.lambda == Approx(expected).epsilon(1e-9));
  CHECK(first.mode == BreakMode::shear);
  // Without internal friction the same scene breaks earlier.
  scene.strength->internal_friction = 0;
  CHECK(-first_break(scene).lambda < 0.9 * expected);
}
