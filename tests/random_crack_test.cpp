// A tensile crack runs perpendicular to the load on a random lattice, whatever the load's
// angle or the notch's lean; on the triangular lattice it does not (notched_plate.h).
#include <catch2/catch.hpp>
#include <sstream>

#include "hard_case_checks.h"
#include "notched_plate.h"

using namespace latfrac;
using namespace latfrac::testing;

TEST_CASE("Random lattice: a crack from a leaning notch runs perpendicular to the load",
          "[fracture][random]") {
  const double lean = GENERATE(0.0, 20.0, 45.0);
  double sum = 0;
  std::ostringstream seen;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const RunResult result = run_scene(notched_plate(LatticeKind::random, lean, seed), quiet());
    const CrackDirection crack = crack_direction(result);
    seen << " " << crack.degrees << " (" << crack.bonds << " bonds)";
    CHECK(crack.bonds >= 20);  // through most of the 32 spacings below the tip
    sum += crack.degrees;
  }
  INFO("notch " << lean << " deg: crack angles from the vertical, seeds 1-5:" << seen.str());
  CHECK(std::abs(sum / 5) < 5.0);
}

TEST_CASE("Triangular lattice: a crack from a leaning notch does not run perpendicular to the load",
          "[fracture][random]") {
  // The contrast, and the proof that the measurement above can fail: the same plates on
  // the triangular lattice, whose rows lie at 0 and +-60 degrees from the load. Measured:
  // the crack from the 20 degree notch runs at about -9 degrees, the one from the 45
  // degree notch along the horizontal rows (90 degrees).
  const double lean = GENERATE(20.0, 45.0);
  const CrackDirection crack =
      crack_direction(run_scene(notched_plate(LatticeKind::regular, lean, 0), quiet()));
  INFO("notch " << lean << " deg: crack at " << crack.degrees << " deg from the vertical ("
                << crack.bonds << " bonds)");
  CHECK(crack.bonds >= 20);
  CHECK(std::abs(crack.degrees) > 5.0);
}

TEST_CASE("Random lattice: a crack under a rotated load runs perpendicular to it",
          "[fracture][random]") {
  // The load itself turned by 0, 20 and 45 degrees (every face node moved as the uniaxial
  // strain along the load would move it), a slit perpendicular to the load in the middle:
  // the crack's mean direction over seeds 1-5 stays the slit's within 5 degrees.
  const double load = GENERATE(0.0, 20.0, 45.0);
  double sum = 0;
  std::ostringstream seen;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const CrackDirection crack = rotated_load_crack(LatticeKind::random, load, seed);
    seen << " " << crack.degrees << " (" << crack.bonds << " bonds)";
    CHECK(crack.bonds >= 10);
    sum += crack.degrees;
  }
  const CrackDirection triangular = rotated_load_crack(LatticeKind::regular, load, 0);
  INFO("load at " << load << " deg: crack from the slit's direction, seeds 1-5:" << seen.str()
                  << "; triangular lattice " << triangular.degrees << " (" << triangular.bonds
                  << " bonds)");
  CHECK(std::abs(sum / 5) < 5.0);
  // The contrast: the triangular lattice turns the crack by 20 degrees (load at 0) and 26
  // (load at 45) towards its rows; at 20 degrees by only 8, so that case is not checked.
  if (load != 20.0) CHECK(std::abs(triangular.degrees) > 5.0);
}
