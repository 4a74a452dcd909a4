// Failure indices, break modes and strength resolution against hand computations.
#include "latfrac/criteria/criterion.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <numbers>

#include "criterion_calls.h"
#include "sampling.h"
#include "latfrac/base/error.h"

using namespace latfrac;
using namespace latfrac::testing;

namespace {
constexpr double MPa = 1e6;
const double sqrt3 = std::sqrt(3.0);
double radians(double degrees) { return degrees * std::numbers::pi / 180; }
}  // namespace

TEST_CASE("stress-based failure indices match hand values", "[criterion]") {
  const double sigma0 = 50 * MPa, tau0 = 40 * MPa;
  // sigma_n / sigma0 = 30/50 = 0.6, tau / tau0 = 20/40 = 0.5.
  const FailureIndex tensile = failure_index(Criterion::tensile, 30 * MPa, 20 * MPa, sigma0, tau0);
  CHECK(tensile.value == Approx(0.6));
  CHECK(tensile.mode == BreakMode::tensile);

  const FailureIndex either =
      failure_index(Criterion::tensile_or_shear, 30 * MPa, 20 * MPa, sigma0, tau0);
  CHECK(either.value == Approx(0.6));
  CHECK(either.mode == BreakMode::tensile);

  const FailureIndex ellipse = failure_index(Criterion::elliptic, 30 * MPa, 20 * MPa, sigma0, tau0);
  CHECK(ellipse.value == Approx(0.36 + 0.25));
  CHECK(ellipse.mode == BreakMode::tensile);

  // tau / tau0 = 36/40 = 0.9 beats 0.6: shear.
  const FailureIndex sheared =
      failure_index(Criterion::tensile_or_shear, 30 * MPa, 36 * MPa, sigma0, tau0);
  CHECK(sheared.value == Approx(0.9));
  CHECK(sheared.mode == BreakMode::shear);
  CHECK(failure_index(Criterion::elliptic, 30 * MPa, 36 * MPa, sigma0, tau0).value ==
        Approx(0.36 + 0.81));
}

TEST_CASE("compression never drives failure", "[criterion]") {
  const double sigma0 = 50 * MPa, tau0 = 40 * MPa;
  CHECK(failure_index(Criterion::tensile, -80 * MPa, 20 * MPa, sigma0, tau0).value == 0);
  const FailureIndex either =
      failure_index(Criterion::tensile_or_shear, -80 * MPa, 20 * MPa, sigma0, tau0);
  CHECK(either.value == Approx(0.5));
  CHECK(either.mode == BreakMode::shear);
  const FailureIndex ellipse =
      failure_index(Criterion::elliptic, -80 * MPa, 20 * MPa, sigma0, tau0);
  CHECK(ellipse.value == Approx(0.25));
  CHECK(ellipse.mode == BreakMode::shear);
}

TEST_CASE("a stress tensor resolved on a bond direction matches Mohr's circle", "[criterion]") {
  // sigma_xx = 20 MPa, sigma_zz = -60 MPa, no shear; a bond at 60 degrees from x in the
  // x-z plane: sigma_n = xx cos^2 + zz sin^2 = 5 - 45 = -40 MPa, and
  // tau = |xx - zz| sin cos = 80 (sqrt3 / 4) = 34.64 MPa. sigma_yy plays no part.
  const VoigtStress stress{20 * MPa, 99 * MPa, -60 * MPa, 0, 0, 0};
  const Eigen::Vector3d n(0.5, 0, sqrt3 / 2);
  const ResolvedStress r = resolve_on(stress, n);
  CHECK(r.normal == Approx(-40 * MPa));
  CHECK(r.shear.norm() == Approx(20 * sqrt3 * MPa));
  CHECK(std::abs(r.shear.dot(n)) < 1e-9 * MPa);
  // Pure shear sigma_xz = 30 MPa on a horizontal bond: no normal stress, tau = 30 MPa along z.
  const ResolvedStress pure = resolve_on({0, 0, 0, 0, 30 * MPa, 0}, Eigen::Vector3d(1, 0, 0));
  CHECK(pure.normal == 0);
  CHECK(pure.shear.z() == Approx(30 * MPa));
}

TEST_CASE("failure_index accepts an infinite tau0 and refuses Drucker-Prager", "[criterion]") {
  const double inf = std::numeric_limits<double>::infinity();
  CHECK(failure_index(Criterion::elliptic, 25 * MPa, 1e9, 50 * MPa, inf).value == Approx(0.25));
  CHECK_THROWS_AS(failure_index(Criterion::drucker_prager, 1, 1, 1, 1), Error);
}

TEST_CASE("tau0 derived from the friction angle", "[criterion]") {
  // psi = 30: (1 + 1/2) / (2 sqrt3 / 2) = 1.5 / sqrt3 = sqrt3 / 2 = 0.8660254...
  CHECK(derived_tau0(50 * MPa, 30, 1) == Approx(50 * MPa * 0.8660254037844386));
  // The paper's psi = 34: sin 34 = 0.5591929, cos 34 = 0.8290376,
  // 1.5591929 / 1.6580751 = 0.9403632, so tau0 = 47.018 MPa for sigma0 = 50 MPa.
  CHECK(derived_tau0(50 * MPa, 34, 1) == Approx(47.01816e6).epsilon(1e-6));
  CHECK(derived_tau0(50 * MPa, 34, 3) == Approx(3 * 47.01816e6).epsilon(1e-6));
}

TEST_CASE("resolve_criterion derives, passes through and rejects", "[criterion]") {
  Strength s;
  s.criterion = Criterion::elliptic;
  s.sigma0 = 50 * MPa;
  s.friction_angle = 30;
  s.tau0_factor = 2;
  CriterionParameters p = resolve_criterion(s, 3);
  CHECK(p.tau0 == Approx(2 * 50 * MPa * 0.8660254037844386));
  // psi = 30, 3-D: alpha = 1 / (2.5 sqrt3), k / c = 6 (sqrt3 / 2) / (2.5 sqrt3) = 1.2.
  CHECK(p.dp_alpha == Approx(0.4 / sqrt3));
  CHECK(p.dp_k_per_cohesion == Approx(1.2));
  // 2-D: tan 30 = 1/sqrt3, sqrt(9 + 12/3) = sqrt13: alpha = 1/sqrt39, k / c = 3/sqrt13.
  p = resolve_criterion(s, 2);
  CHECK(p.dp_alpha == Approx(1 / std::sqrt(39.0)));
  CHECK(p.dp_k_per_cohesion == Approx(3 / std::sqrt(13.0)));

  s.tau0 = 20 * MPa;
  s.tau0_factor = 1;
  CHECK(resolve_criterion(s, 3).tau0 == 20 * MPa);

  Strength tensile;
  tensile.criterion = Criterion::tensile;
  tensile.sigma0 = 10 * MPa;
  p = resolve_criterion(tensile, 2);
  CHECK(std::isinf(p.tau0));
  CHECK(std::isnan(p.dp_alpha));

  Strength missing = tensile;
  missing.criterion = Criterion::elliptic;
  CHECK_THROWS_AS(resolve_criterion(missing, 2), InputError);
  missing.criterion = Criterion::tensile_or_shear;
  CHECK_THROWS_AS(resolve_criterion(missing, 2), InputError);
  missing.criterion = Criterion::drucker_prager;
  missing.tau0 = 5 * MPa;
  CHECK_THROWS_AS(resolve_criterion(missing, 2), InputError);
  Strength weak = tensile;
  weak.sigma0 = 0;
  CHECK_THROWS_AS(resolve_criterion(weak, 2), InputError);
}

TEST_CASE("Drucker-Prager invariants and hand values", "[criterion]") {
  // psi = 30, 3-D, c = 10 MPa: alpha = 0.4/sqrt3, k = 12 MPa.
  const double alpha = 0.4 / sqrt3, k = 12 * MPa;
  // Uniaxial compression q = 20 MPa: I1 = -q, sqrt(J2) = q/sqrt3,
  // f = (20/sqrt3) (1 - 0.4) / 12 = 1/sqrt3.
  const VoigtStress uniaxial{0, 0, -20 * MPa, 0, 0, 0};
  CHECK(first_invariant(uniaxial) == -20 * MPa);
  CHECK(second_deviatoric_invariant(uniaxial) == Approx(400 * MPa * MPa / 3));
  const FailureIndex f = drucker_prager_index(uniaxial, alpha, k);
  CHECK(f.value == Approx(1 / sqrt3));
  CHECK(f.mode == BreakMode::shear);

  // A hydrostatic compression -p lowers f by alpha 3p / k.
  const double p = 7 * MPa;
  const VoigtStress pressed{-p, -p, -20 * MPa - p, 0, 0, 0};
  CHECK(drucker_prager_index(pressed, alpha, k).value ==
        Approx(1 / sqrt3 - alpha * 3 * p / k).epsilon(1e-13));

  // Pure shear: J2 = tau^2, I1 = 0, f = tau / k; any Voigt shear slot.
  for (int slot = 3; slot < 6; ++slot) {
    VoigtStress shear{};
    shear[slot] = 6 * MPa;
    CHECK(drucker_prager_index(shear, alpha, k).value == Approx(0.5));
  }

  // Hydrostatic tension: sqrt(J2) = 0, the mean-stress term decides: tensile mode.
  const FailureIndex pulled = drucker_prager_index({MPa, MPa, MPa, 0, 0, 0}, alpha, k);
  CHECK(pulled.value == Approx(alpha * 3 * MPa / k));
  CHECK(pulled.mode == BreakMode::tensile);
}

TEST_CASE("3-D Drucker-Prager constants reproduce Mohr-Coulomb in compression", "[criterion]") {
  const double c = 10 * MPa;
  for (double psi : {0.0, 20.0, 30.0, 34.0, 45.0}) {
    const DruckerPragerConstants dp = drucker_prager_constants(psi, 3);
    const double k = dp.k_per_cohesion * c;
    const double s = std::sin(radians(psi)), cs = std::cos(radians(psi));
    // Uniaxial compressive strength 2 c cos psi / (1 - sin psi).
    const double strength = 2 * c * cs / (1 - s);
    CHECK(drucker_prager_index({0, 0, -strength, 0, 0, 0}, dp.alpha, k).value == Approx(1));
    // The compression meridian (two equal larger principal stresses): Mohr circle of
    // centre C and radius R = c cos psi - C sin psi touches the Coulomb line.
    for (double centre : {-60 * MPa, -20 * MPa, 0.0}) {
      const double radius = c * cs - centre * s;
      const double larger = centre + radius, smaller = centre - radius;
      CHECK(drucker_prager_index({larger, larger, smaller, 0, 0, 0}, dp.alpha, k).value ==
            Approx(1));
    }
  }
}

TEST_CASE("2-D Drucker-Prager constants reproduce Mohr-Coulomb in plane strain", "[criterion]") {
  // Plane-strain plastic flow (associated, eps_yy = 0) fixes the out-of-plane deviator at
  // s_yy = -2 alpha sqrt(J2). With in-plane principal stresses C +- R and sigma_yy = C + d,
  // J2 = R^2 + d^2/3 and s_yy = 2d/3, so d = -3 alpha R / sqrt(1 - 3 alpha^2). On the
  // Coulomb line R = c cos psi - C sin psi this state must give f = 1.
  const double c = 10 * MPa;
  for (double psi : {0.0, 30.0, 45.0}) {
    const DruckerPragerConstants dp = drucker_prager_constants(psi, 2);
    const double s = std::sin(radians(psi)), cs = std::cos(radians(psi));
    for (double centre : {-50 * MPa, -5 * MPa, 0.0}) {
      const double radius = c * cs - centre * s;
      const double d = -3 * dp.alpha * radius / std::sqrt(1 - 3 * dp.alpha * dp.alpha);
      const VoigtStress stress{centre + radius, centre + d, centre - radius, 0, 0, 0};
      CHECK(drucker_prager_index(stress, dp.alpha, dp.k_per_cohesion * c).value == Approx(1));
    }
  }
  // With the elastic sigma_yy = nu (xx + zz) instead, the same Coulomb state is not at f = 1:
  // psi = 30, nu = 0.2, C = -5c, R = c cos psi - C sin psi = 33.66 MPa gives f = 2.2402
  // (docs/criteria.md quotes this).
  {
    const DruckerPragerConstants dp = drucker_prager_constants(30, 2);
    const double centre = -5 * c, radius = c * std::cos(radians(30)) - centre * 0.5;
    const VoigtStress elastic{centre + radius, 0.2 * 2 * centre, centre - radius, 0, 0, 0};
    CHECK(drucker_prager_index(elastic, dp.alpha, dp.k_per_cohesion * c).value ==
          Approx(2.2402222439863455));
  }
  // psi = 0: pure in-plane shear fails at tau = c.
  const DruckerPragerConstants tresca = drucker_prager_constants(0, 2);
  CHECK(drucker_prager_index({0, 0, 0, 0, c, 0}, tresca.alpha, tresca.k_per_cohesion * c).value ==
        Approx(1));
}

namespace {

// The largest f over planes by brute force: normals sampled densely in the x-z plane (2-D)
// or over the unit sphere (3-D), each plane's sigma_n and tau from resolve_on.
double sampled_critical_plane(Criterion criterion, const VoigtStress& stress, int dim,
                              double sigma0, double tau0) {
  double best = 0;
  for_each_sampled_plane(dim, [&](const Eigen::Vector3d& n) {
    const ResolvedStress r = resolve_on(stress, n);
    best = std::max(best, failure_index(criterion, r.normal, r.shear.norm(), sigma0, tau0).value);
  });
  return best;
}

}  // namespace

TEST_CASE("the critical-plane reading: Rankine, Tresca and the elliptic maximum by hand",
          "[criterion]") {
  const double sigma0 = 50 * MPa, tau0 = 40 * MPa;
  // Uniaxial tension of 30 MPa along 30 degrees from x in the x-z plane: s1 = 30 MPa, s3 = 0,
  // whatever the direction. xx = 30 cos^2 30 = 22.5, zz = 7.5, xz = 30 sin30 cos30 = 12.99.
  const VoigtStress tilted{22.5 * MPa, 0, 7.5 * MPa, 0, 7.5 * sqrt3 * MPa, 0};
  for (int dim : {2, 3}) {
    CHECK(critical_plane_index(Criterion::tensile, tilted, dim, sigma0, tau0).value ==
          Approx(0.6));
    // Tresca: r = 15 MPa; 15/40 < 0.6, so tensile.
    const FailureIndex either =
        critical_plane_index(Criterion::tensile_or_shear, tilted, dim, sigma0, tau0);
    CHECK(either.value == Approx(0.6));
    CHECK(either.mode == BreakMode::tensile);
  }
  // 2-D: the out-of-plane yy plays no part; in 3-D it is the largest principal stress.
  const VoigtStress out_of_plane{0, 40 * MPa, -20 * MPa, 0, 0, 0};
  CHECK(critical_plane_index(Criterion::tensile, out_of_plane, 2, sigma0, tau0).value == 0);
  CHECK(critical_plane_index(Criterion::tensile, out_of_plane, 3, sigma0, tau0).value ==
        Approx(0.8));
  // Lithostatic compression (xx = zz / 4 = -50 MPa, zz = -200 MPa): no plane is in tension,
  // the largest shear is r = 75 MPa, so tensile f = 0, tensile_or_shear f = 75/40 = 1.875
  // (shear) and elliptic f = 1.875^2 (on the 45 degree plane).
  const VoigtStress lithostatic{-50 * MPa, -50 * MPa, -200 * MPa, 0, 0, 0};
  CHECK(critical_plane_index(Criterion::tensile, lithostatic, 2, sigma0, tau0).value == 0);
  const FailureIndex shear =
      critical_plane_index(Criterion::tensile_or_shear, lithostatic, 2, sigma0, tau0);
  CHECK(shear.value == Approx(1.875));
  CHECK(shear.mode == BreakMode::shear);
  CHECK(critical_plane_index(Criterion::elliptic, lithostatic, 2, sigma0, tau0).value ==
        Approx(1.875 * 1.875));
  // Pure shear xz = 30 MPa with sigma0 > tau0 (the elliptic piece is concave): c = 0,
  // r = 30, g(x) = (30 x / 50)^2 + (30^2 / 40^2)(1 - x^2) is largest at x = 0: 0.5625.
  CHECK(critical_plane_index(Criterion::elliptic, {0, 0, 0, 0, 30 * MPa, 0}, 2, sigma0, tau0)
            .value == Approx(0.5625));
  // Drucker-Prager is a function of the tensor's invariants: its tensor index is that
  // function (psi = 30 deg, as criterion_object sets it), whatever the reading.
  const DruckerPragerConstants dp = drucker_prager_constants(30, 2);
  CHECK(criterion_object(Criterion::drucker_prager, 2)->tensor_index(tilted, {sigma0, tau0}).value ==
        Approx(drucker_prager_index(tilted, dp.alpha, dp.k_per_cohesion * tau0).value));
}

TEST_CASE("the critical-plane reading equals the largest f over sampled planes", "[criterion]") {
  const VoigtStress states[] = {
      {20 * MPa, 5 * MPa, -60 * MPa, 0, 10 * MPa, 0},
      {30 * MPa, -10 * MPa, 25 * MPa, 8 * MPa, -5 * MPa, 12 * MPa},
      {-80 * MPa, -20 * MPa, -30 * MPa, 3 * MPa, 40 * MPa, -7 * MPa},
      {10 * MPa, 10 * MPa, 10 * MPa, 0, 0, 0},
  };
  // sigma0 above, equal to and below tau0: the elliptic piece concave, flat and convex.
  for (double tau0 : {30 * MPa, 50 * MPa, 90 * MPa}) {
    for (const VoigtStress& state : states) {
      for (int dim : {2, 3}) {
        for (Criterion c : {Criterion::tensile, Criterion::tensile_or_shear, Criterion::elliptic}) {
          INFO("tau0 " << tau0 << " dim " << dim << " criterion " << static_cast<int>(c));
          VoigtStress s = state;
          if (dim == 2) s[3] = s[5] = 0;  // plane strain: no yz, xy
          const double exact = critical_plane_index(c, s, dim, 50 * MPa, tau0).value;
          const double sampled = sampled_critical_plane(c, s, dim, 50 * MPa, tau0);
          CHECK(exact >= sampled * (1 - 1e-12));
          CHECK(exact == Approx(sampled).epsilon(2e-4));
        }
      }
    }
  }
}
