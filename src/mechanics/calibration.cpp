// Spring constants from the elastic moduli, and the Cauchy-Born bond sum that checks them.
#include "latfrac/mechanics/calibration.h"

#include <cmath>
#include <sstream>

#include "latfrac/base/error.h"
#include "latfrac/mechanics/random_calibration.h"

namespace latfrac {
namespace {

double lame_lambda(const Material& m) {
  return m.young * m.poisson / ((1 + m.poisson) * (1 - 2 * m.poisson));
}
double lame_mu(const Material& m) { return m.young / (2 * (1 + m.poisson)); }

// Voigt index of the symmetric pair (i, j).
int voigt(int i, int j) {
  if (i == j) return i;
  const int sum = i + j;  // (1,2)->3 yz, (0,2)->4 xz, (0,1)->5 xy
  return sum == 3 ? 3 : (sum == 2 ? 4 : 5);
}

}  // namespace

void validate_material(const Material& material, const char* where) {
  std::ostringstream message;
  if (!(material.young > 0) || !std::isfinite(material.young)) {
    message << where << ".young: must be a positive modulus in Pa";
    throw InputError(message.str());
  }
  if (!(material.poisson > -1) || !(material.poisson <= 0.25)) {
    message << where << ".poisson: " << material.poisson
            << " is outside -1 < nu <= 0.25; above 1/4 the lattice's shear springs would be "
               "negative (ks < 0)";
    throw InputError(message.str());
  }
}

void validate_material(const Material& material, int dim, LatticeKind kind, const char* where) {
  if (kind == LatticeKind::random) {
    random_spring_parameters(dim, material, where);
  } else {
    validate_material(material, where);
  }
}

SpringConstants spring_constants(int dim, const Material& material, double spacing) {
  validate_material(material);
  SpringConstants k;
  if (dim == 2) {
    const double lambda = lame_lambda(material), mu = lame_mu(material);
    k.normal = 2 / std::sqrt(3.0) * (lambda + mu);
    k.shear = 2 / std::sqrt(3.0) * (mu - lambda);
  } else {
    const double nu = material.poisson;
    k.normal = std::sqrt(2.0) / 5 * material.young * spacing / (1 - 2 * nu);
    k.shear = k.normal * (1 - 4 * nu) / (1 + nu);
  }
  return k;
}

VoigtTensor isotropic_tensor(const Material& material) {
  const double lambda = lame_lambda(material), mu = lame_mu(material);
  VoigtTensor c = VoigtTensor::Zero();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) c(i, j) = lambda;
    c(i, i) = lambda + 2 * mu;
    c(i + 3, i + 3) = mu;
  }
  return c;
}

// A bond's energy under the affine strain eps is (1/2) du . K_b du with du = L0 eps n,
// K_b = kn n n + ks (I - n n). Each bond is shared by two nodes, hence 1/(2 V0) per node.
VoigtTensor lattice_tensor(int dim, const Material& material, double spacing, bool next_nearest) {
  LatticeSpec spec;
  spec.dim = dim;
  spec.spacing = spacing;
  spec.next_nearest = next_nearest;
  spec.size = {8 * spacing, 8 * spacing, 8 * spacing};
  const Lattice lattice = build_lattice(spec);
  // The node nearest the centre has a complete neighbourhood.
  const Vec3 centre = lattice.extent / 2;
  std::int64_t middle = 0;
  for (std::int64_t n = 1; n < lattice.node_count(); ++n) {
    if ((lattice.positions[n] - centre).norm() < (lattice.positions[middle] - centre).norm())
      middle = n;
  }
  const SpringConstants k = spring_constants(dim, material, spacing);
  double c[3][3][3][3] = {};
  for (std::int64_t b = 0; b < lattice.bond_count(); ++b) {
    const Bond& bond = lattice.bonds[b];
    if (bond.i != middle && bond.j != middle) continue;
    const double scale = bond.kind == BondKind::next_nearest ? next_nearest_fraction : 1.0;
    const double kn = scale * k.normal, ks = scale * k.shear;
    const Vec3& n = lattice.bond_direction[b];
    const double length = lattice.bond_length[b];
    // d^2/d eps_ij d eps_kl of (1/2)[kn (n.eps.n)^2 + ks (|eps n|^2 - (n.eps.n)^2)] L0^2,
    // symmetrised over (i, j) and (k, l).
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int p = 0; p < 3; ++p)
          for (int q = 0; q < 3; ++q) {
            double term = (kn - ks) * n[i] * n[j] * n[p] * n[q];
            const double shear = 0.25 * ((i == p) * n[j] * n[q] + (i == q) * n[j] * n[p] +
                                         (j == p) * n[i] * n[q] + (j == q) * n[i] * n[p]);
            term += ks * shear;
            c[i][j][p][q] += term * length * length / (2 * lattice.node_volume);
          }
  }
  VoigtTensor voigt_c = VoigtTensor::Zero();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int p = 0; p < 3; ++p)
        for (int q = 0; q < 3; ++q) voigt_c(voigt(i, j), voigt(p, q)) = c[i][j][p][q];
  return voigt_c;
}

}  // namespace latfrac
