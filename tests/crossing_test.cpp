// Closed-form crossings against sampling + bisection of f, and hand-solved edge cases.
#include "latfrac/criteria/crossing.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>

#include "latfrac/criteria/criterion.h"
#include "criterion_calls.h"
#include "sampling.h"
#include "latfrac/base/error.h"

using namespace latfrac;
using namespace latfrac::testing;

namespace {

constexpr double MPa = 1e6;
constexpr double inf = std::numeric_limits<double>::infinity();
const double sqrt3 = std::sqrt(3.0);

double index_at(Criterion criterion, const AffineBondStress& s, double sigma0, double tau0,
                double l) {
  return failure_index(criterion, s.normal0 + l * s.normal1, (s.shear0 + l * s.shear1).norm(),
                       sigma0, tau0)
      .value;
}

VoigtStress stress_at(const VoigtStress& s0, const VoigtStress& s1, double l) {
  VoigtStress s;
  for (int i = 0; i < 6; ++i) s[i] = s0[i] + l * s1[i];
  return s;
}

struct Outcomes {
  int at_from = 0, crossing = 0, none = 0;
};

void compare(double exact, double sampled, double from, double to, Outcomes& outcomes) {
  if (sampled == inf) {
    CHECK(exact == inf);
    ++outcomes.none;
    return;
  }
  (sampled == from ? outcomes.at_from : outcomes.crossing)++;
  CHECK(exact == Approx(sampled).margin(1e-10 * std::max(std::abs(sampled), to - from)));
}

}  // namespace

TEST_CASE("real_roots is free of cancellation and handles degenerate cases", "[crossing]") {
  // x^2 - 1e8 x + 1 = 0: the textbook formula loses about half the digits of the small root.
  QuadraticRoots r = real_roots(1, -1e8, 1);
  REQUIRE(r.count == 2);
  CHECK(r.root[0] == Approx(1e-8).epsilon(1e-14));
  CHECK(r.root[1] == Approx(1e8).epsilon(1e-14));
  r = real_roots(0, 2, -4);
  REQUIRE(r.count == 1);
  CHECK(r.root[0] == 2);
  CHECK(real_roots(0, 0, 1).count == 0);
  CHECK(real_roots(1, 0, 1).count == 0);
  // (x - 1)^2 / 3 with rounded coefficients: a double root, not "no root".
  r = real_roots(1.0 / 3, -2.0 / 3, 1.0 / 3);
  REQUIRE(r.count == 2);
  CHECK(r.root[0] == Approx(1).epsilon(1e-7));
  CHECK(r.root[1] == Approx(1).epsilon(1e-7));
  r = real_roots(-2, 2, 4);  // -2 (x - 2)(x + 1)
  REQUIRE(r.count == 2);
  CHECK(r.root[0] == Approx(-1));
  CHECK(r.root[1] == Approx(2));
}

TEST_CASE("stress-based crossings agree with sampling on random affine paths", "[crossing]") {
  const double sigma0 = 50 * MPa;
  std::mt19937_64 rng(20140243);
  std::uniform_real_distribution<double> unit(-1, 1), positive(0, 1);
  for (Criterion criterion :
       {Criterion::tensile, Criterion::tensile_or_shear, Criterion::elliptic}) {
    Outcomes outcomes;
    for (int trial = 0; trial < 2000; ++trial) {
      const double tau0 = trial % 10 == 9 ? inf : 40 * MPa;
      const double shear_scale = 40 * MPa;
      AffineBondStress s;
      s.normal0 = 1.5 * sigma0 * unit(rng);
      s.normal1 = 3 * sigma0 * unit(rng);
      s.shear0 = shear_scale * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
      s.shear1 = 2 * shear_scale * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
      if (trial % 3 == 0) s.shear0.y() = s.shear1.y() = 0;  // a 2-D bond
      const double from = unit(rng), to = from + 2 * positive(rng);
      const auto f = [&](double l) { return index_at(criterion, s, sigma0, tau0, l); };
      const double exact = first_crossing(criterion, s, sigma0, tau0, from, to);
      compare(exact, sampled_crossing(f, from, to), from, to, outcomes);
      if (exact > from && exact < inf) CHECK(f(exact) == Approx(1).epsilon(1e-9));
    }
    INFO("criterion " << static_cast<int>(criterion));
    CHECK(outcomes.at_from > 50);
    CHECK(outcomes.crossing > 300);
    CHECK(outcomes.none > 50);
  }
}

TEST_CASE("where index() grows with stress, f on an affine path stays below its ends' bound",
          "[crossing]") {
  // The crossing search skips a bond when index(the larger sigma_n of the ends, the larger
  // |tau| of the ends) < 1 (FailureCriterion::index_grows_with_stress). Sampled f along
  // random paths, with and without internal friction, never exceeds that bound.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1, 1), positive(0, 1);
  const double sigma0 = 50 * MPa, tau0 = 40 * MPa;
  int claimed = 0;
  for (Criterion criterion : {Criterion::tensile_or_shear, Criterion::elliptic}) {
    for (double mu : {0.0, 0.6}) {
      const auto object = criterion_object(criterion, 2, mu);
      if (!object->index_grows_with_stress()) continue;
      ++claimed;
      double worst = 0;
      for (int trial = 0; trial < 500; ++trial) {
        AffineBondStress s;
        s.normal0 = 2 * sigma0 * unit(rng);
        s.normal1 = 4 * sigma0 * unit(rng);
        s.shear0 = tau0 * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
        s.shear1 = 2 * tau0 * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
        const double from = unit(rng), to = from + 2 * positive(rng);
        const auto normal = [&](double l) { return s.normal0 + l * s.normal1; };
        const auto shear = [&](double l) { return (s.shear0 + l * s.shear1).norm(); };
        const double bound = object->index(std::max(normal(from), normal(to)),
                                           std::max(shear(from), shear(to)), {sigma0, tau0}).value;
        for (int k = 0; k <= 64; ++k) {
          const double l = from + (to - from) * k / 64;
          worst = std::max(worst, object->index(normal(l), shear(l), {sigma0, tau0}).value / bound);
        }
      }
      INFO("criterion " << static_cast<int>(criterion) << ", mu " << mu << ": largest f / bound " << worst);
      CHECK(worst <= 1 + 1e-12);
    }
  }
  CHECK(claimed == 4);
}

TEST_CASE("Drucker-Prager crossings agree with sampling on random affine paths", "[crossing]") {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1, 1), positive(0, 1);
  Outcomes outcomes;
  for (int trial = 0; trial < 3000; ++trial) {
    const DruckerPragerConstants dp = drucker_prager_constants(45 * positive(rng), 2 + trial % 2);
    const double k = dp.k_per_cohesion * 20 * MPa;
    VoigtStress s0, s1;
    const double mean0 = 40 * MPa * (unit(rng) - 0.5), mean1 = 60 * MPa * unit(rng);
    for (int i = 0; i < 6; ++i) {
      s0[i] = 15 * MPa * unit(rng) + (i < 3 ? mean0 : 0);
      s1[i] = 30 * MPa * unit(rng) + (i < 3 ? mean1 : 0);
    }
    const double from = unit(rng), to = from + 2 * positive(rng);
    const auto f = [&](double l) {
      return drucker_prager_index(stress_at(s0, s1, l), dp.alpha, k).value;
    };
    const double exact = first_crossing_drucker_prager(s0, s1, dp.alpha, k, from, to);
    compare(exact, sampled_crossing(f, from, to), from, to, outcomes);
    if (exact > from && exact < inf) CHECK(f(exact) == Approx(1).epsilon(1e-9));
  }
  CHECK(outcomes.at_from > 50);
  CHECK(outcomes.crossing > 500);
  CHECK(outcomes.none > 50);
}

TEST_CASE("crossings at and next to the ends of the interval", "[crossing]") {
  const double sigma0 = 50 * MPa, tau0 = 40 * MPa;
  AffineBondStress s;
  s.normal1 = sigma0;  // sn = sigma0 l: f = 1 at l = 1
  CHECK(first_crossing(Criterion::tensile, s, sigma0, tau0, 1, 2) == 1);
  CHECK(first_crossing(Criterion::tensile, s, sigma0, tau0, 1.5, 2) == 1.5);
  CHECK(first_crossing(Criterion::tensile, s, sigma0, tau0, 0, 1) == 1);
  CHECK(first_crossing(Criterion::tensile, s, sigma0, tau0, 0, 0.999) == inf);
  CHECK(first_crossing(Criterion::tensile, s, sigma0, tau0, -3, 7) == Approx(1));
  // Just below 1 at 'from': the crossing is strictly after it.
  const double from = 1 - 1e-14;
  const double l = first_crossing(Criterion::tensile, s, sigma0, tau0, from, 2);
  CHECK(l > from);
  CHECK(l == Approx(1).epsilon(1e-15));
}

TEST_CASE("shear paths tangent to f = 1", "[crossing]") {
  const double sigma0 = 50 * MPa, tau0 = 40 * MPa;
  // t(l) = tau0 (l - 1/2, h, 0): tau / tau0 = sqrt((l - 1/2)^2 + h^2), smallest at l = 1/2.
  AffineBondStress s;
  s.shear0 = tau0 * Eigen::Vector3d(-0.5, 1, 0);
  s.shear1 = tau0 * Eigen::Vector3d(1, 0, 0);
  for (Criterion c : {Criterion::tensile_or_shear, Criterion::elliptic}) {
    // h = 1: the path touches the circle tau = tau0 from outside; f >= 1 everywhere.
    CHECK(first_crossing(c, s, sigma0, tau0, 0, 1) == 0);
    CHECK(first_crossing(c, s, sigma0, tau0, 0.5, 1) == 0.5);
  }
  // h^2 = 1 - 1e-12: f dips just below 1 at l = 1/2 and returns at l = 1/2 + 1e-6.
  s.shear0.y() = tau0 * std::sqrt(1 - 1e-12);
  for (Criterion c : {Criterion::tensile_or_shear, Criterion::elliptic}) {
    const double l = first_crossing(c, s, sigma0, tau0, 0.5, 1);
    CHECK(l == Approx(0.5 + 1e-6).margin(1e-10));
  }
  // No slope at all (a = b = 0): never.
  s.shear0 = tau0 * Eigen::Vector3d(0, 0.8, 0);
  s.shear1.setZero();
  CHECK(first_crossing(Criterion::elliptic, s, sigma0, tau0, 0.5, 1) == inf);
}

TEST_CASE("the normal stress changes sign inside the interval", "[crossing]") {
  const double sigma0 = 50 * MPa, tau0 = 40 * MPa;
  // sn = sigma0 (l - 1), tau = 0.6 tau0: elliptic f = 1 where sn = 0.8 sigma0, l = 1.8.
  AffineBondStress rising;
  rising.normal0 = -sigma0;
  rising.normal1 = sigma0;
  rising.shear0 = Eigen::Vector3d(0, 0, 0.6 * tau0);
  CHECK(first_crossing(Criterion::elliptic, rising, sigma0, tau0, 0, 3) == Approx(1.8));
  CHECK(first_crossing(Criterion::tensile, rising, sigma0, tau0, 0, 3) == Approx(2));
  CHECK(first_crossing(Criterion::tensile_or_shear, rising, sigma0, tau0, 0, 3) == Approx(2));

  // sn = sigma0 (1/2 - 2 l), tau = tau0 l / 2. Past l = 1/4 the bond is in compression and
  // only (tau/tau0)^2 = l^2/4 counts: f = 1 at l = 2. Squaring sn regardless would give
  // l = 3/4, where (sn/sigma0)^2 = 1.
  AffineBondStress falling;
  falling.normal0 = 0.5 * sigma0;
  falling.normal1 = -2 * sigma0;
  falling.shear1 = Eigen::Vector3d(0.5 * tau0, 0, 0);
  CHECK(first_crossing(Criterion::elliptic, falling, sigma0, tau0, 0, 3) == Approx(2));
  CHECK(first_crossing(Criterion::tensile, falling, sigma0, tau0, 0, 3) == inf);
  CHECK(first_crossing(Criterion::tensile_or_shear, falling, sigma0, tau0, 0, 3) == Approx(2));
  CHECK(first_crossing(Criterion::tensile_or_shear, falling, sigma0, inf, 0, 3) == inf);
}

TEST_CASE("Drucker-Prager crossings in hand-solved cases", "[crossing]") {
  // psi = 30, 3-D, c = 10 MPa: alpha = 0.4/sqrt3, k = 12 MPa.
  const double alpha = 0.4 / sqrt3, k = 12 * MPa, p = 10 * MPa;
  const VoigtStress zero{};

  // Hydrostatic tension S = p l I: f = 3 alpha p l / k, l* = k / (3 alpha p) = sqrt3.
  // Squared, -(k - 3 alpha p l)^2 = 0 is a double root.
  const VoigtStress hydrostatic{p, p, p, 0, 0, 0};
  CHECK(first_crossing_drucker_prager(zero, hydrostatic, alpha, k, 0, 5) ==
        Approx(sqrt3).epsilon(1e-12));

  // S = l (p I + tau1 e_xy) with tau1 = 3 alpha p: the squared equation loses its l^2 term
  // (J2 = tau1^2 l^2 = (3 alpha p l)^2) and is linear; f = 6 alpha p l / k, l* = k / (6 alpha p).
  const VoigtStress balanced{p, p, p, 0, 0, 3 * alpha * p};
  CHECK(first_crossing_drucker_prager(zero, balanced, alpha, k, 0, 5) ==
        Approx(k / (6 * alpha * p)).epsilon(1e-12));

  // S = l (p I + d e_xy) with d < 3 alpha p: (d l)^2 = (k - 3 alpha p l)^2 has the admissible
  // root l = k / (d + 3 alpha p) and the squared-in root l = k / (3 alpha p - d), where
  // k - alpha I1 < 0 (f = 2 alpha I1 / k - 1 > 1 there). Both lie in the interval; such a
  // root always follows the admissible one, since f > 1 at it and f(from) < 1.
  const double d = 2 * MPa;
  const VoigtStress steep{p, p, p, 0, 0, d};
  const double admissible = k / (d + 3 * alpha * p), spurious = k / (3 * alpha * p - d);
  REQUIRE(spurious < 5);
  CHECK(k - alpha * 3 * p * spurious < 0);
  CHECK(first_crossing_drucker_prager(zero, steep, alpha, k, 0, 5) ==
        Approx(admissible).epsilon(1e-12));
  CHECK(first_crossing_drucker_prager(zero, steep, alpha, k, 2, 5) == 2);  // f(2) > 1

  // Nearly hydrostatic: the two roots of the square are 2e-9 apart (relative), which costs
  // the squared equation half its digits; the crossing must still be exact.
  const VoigtStress almost{p, p, p, 0, 0, 1e-9 * p};
  CHECK(first_crossing_drucker_prager(zero, almost, alpha, k, 0, 5) ==
        Approx(k / (1e-9 * p + 3 * alpha * p)).epsilon(1e-14));

  // Uniaxial compression growing from 0: strength 2 c cos psi / (1 - sin psi) = 20 sqrt3 MPa.
  const VoigtStress squeeze{0, 0, -MPa, 0, 0, 0};
  CHECK(first_crossing_drucker_prager(zero, squeeze, alpha, k, 0, 100) ==
        Approx(20 * sqrt3).epsilon(1e-12));
  // Hydrostatic compression only strengthens: never.
  const VoigtStress pressure{-p, -p, -p, 0, 0, 0};
  CHECK(first_crossing_drucker_prager(zero, pressure, alpha, k, 0, 100) == inf);
  CHECK_THROWS_AS(first_crossing(Criterion::drucker_prager, {}, 1, 1, 0, 1), Error);
}

TEST_CASE("critical-plane crossings: hand-solved and against sampling", "[crossing]") {
  const double sigma0 = 50 * MPa, tau0 = 40 * MPa;
  // Hydrostatic compression -p plus l times uniaxial tension A along a tilted direction:
  // s1(l) = -p + A l, so the tensile criterion crosses at l = (sigma0 + p) / A in 2-D and 3-D.
  const double p = 20 * MPa, A = 35 * MPa;
  const VoigtStress s0{-p, -p, -p, 0, 0, 0};
  const VoigtStress s1{0.75 * A, 0, 0.25 * A, 0, 0.25 * sqrt3 * A, 0};
  for (int dim : {2, 3}) {
    const auto f = [&](double l) {
      return critical_plane_index(Criterion::tensile, stress_at(s0, s1, l), dim, sigma0, tau0).value;
    };
    CHECK(first_crossing_convex(f, 0, 10) == Approx((sigma0 + p) / A).epsilon(1e-14));
    CHECK(first_crossing_convex(f, 0, 1) == inf);         // ends before the crossing
    CHECK(first_crossing_convex(f, 3, 10) == 3);          // already at f >= 1
  }
  // Random affine tensor paths: the bisection finds the sampled first crossing.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1, 1), positive(0, 1);
  Outcomes outcomes;
  for (int trial = 0; trial < 1500; ++trial) {
    const Criterion criterion = trial % 3 == 0   ? Criterion::tensile
                                : trial % 3 == 1 ? Criterion::tensile_or_shear
                                                 : Criterion::elliptic;
    VoigtStress a, b;
    for (int i = 0; i < 6; ++i) {
      a[i] = 30 * MPa * unit(rng);
      b[i] = 50 * MPa * unit(rng);
    }
    const int dim = 2 + trial % 2;
    const auto f = [&](double l) {
      return critical_plane_index(criterion, stress_at(a, b, l), dim, sigma0, tau0).value;
    };
    const double from = unit(rng), to = from + 2 * positive(rng);
    const double exact = first_crossing_convex(f, from, to);
    compare(exact, sampled_crossing(f, from, to), from, to, outcomes);
  }
  CHECK(outcomes.at_from > 50);
  CHECK(outcomes.crossing > 300);
  CHECK(outcomes.none > 50);
}
