// Cauchy-Born: the bond sum reproduces the isotropic elastic tensor of (E, nu).
#include "latfrac/mechanics/calibration.h"

#include <catch2/catch.hpp>

#include "latfrac/base/error.h"
#include "scenes.h"

using namespace latfrac;

namespace {

// Largest entry difference relative to the largest entry, over the Voigt components
// that the dimension carries (2-D plane strain: xx, zz, xz).
double relative_difference(const VoigtTensor& a, const VoigtTensor& b, int dim) {
  const std::vector<int> components =
      dim == 2 ? std::vector<int>{0, 2, 4} : std::vector<int>{0, 1, 2, 3, 4, 5};
  double difference = 0, scale = 0;
  for (int i : components)
    for (int j : components) {
      difference = std::max(difference, std::abs(a(i, j) - b(i, j)));
      scale = std::max(scale, std::abs(b(i, j)));
    }
  return difference / scale;
}

}  // namespace

TEST_CASE("The lattice's elastic tensor is the isotropic tensor of (E, nu)", "[calibration]") {
  const int dim = GENERATE(2, 3);
  const double nu = GENERATE(0.0, 0.1, 0.2, 0.25);
  const Material material = testing::paper_material(nu);
  const VoigtTensor lattice = lattice_tensor(dim, material, 250.0, true);
  const VoigtTensor continuum = isotropic_tensor(material);
  INFO("dim " << dim << ", nu " << nu);
  CHECK(relative_difference(lattice, continuum, dim) < 1e-10);
}

TEST_CASE("3-D HCP without next-nearest bonds is measurably anisotropic", "[calibration]") {
  const Material material = testing::paper_material(0.2);
  const VoigtTensor lattice = lattice_tensor(3, material, 1.0, false);
  // HCP's stacking axis differs from the in-plane axes: C_xxxx != C_zzzz.
  CHECK(std::abs(lattice(0, 0) - lattice(2, 2)) / lattice(0, 0) > 0.05);
  CHECK(relative_difference(lattice, isotropic_tensor(material), 3) > 0.05);
}

TEST_CASE("Spring constants match the closed forms of model.md", "[calibration]") {
  const Material material = testing::paper_material(0.2);
  const SpringConstants k3 = spring_constants(3, material, 2.0);
  CHECK(k3.normal == Approx(std::sqrt(2.0) / 5 * 100e9 * 2.0 / 0.6));
  CHECK(k3.shear == Approx(k3.normal / 6));  // nu = 0.2 gives ks = kn / 6
  // nu = 1/4: no shear springs in either dimension.
  CHECK(spring_constants(2, testing::paper_material(0.25), 1.0).shear == Approx(0).margin(1e-3));
  CHECK(spring_constants(3, testing::paper_material(0.25), 1.0).shear == Approx(0).margin(1e-3));
}

TEST_CASE("Poisson's ratio above 1/4 is rejected because ks would be negative", "[calibration]") {
  const double nu = GENERATE(0.26, 0.3, 0.5, -1.0, -2.0);
  try {
    spring_constants(2, testing::paper_material(nu), 1.0);
    FAIL("no error for nu = " << nu);
  } catch (const InputError& e) {
    CHECK_THAT(e.what(), Catch::Contains("poisson") && Catch::Contains("0.25"));
  }
  Material no_stiffness = testing::paper_material(0.2);
  no_stiffness.young = 0;
  CHECK_THROWS_AS(spring_constants(3, no_stiffness, 1.0), InputError);
}
