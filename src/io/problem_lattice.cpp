// The [lattice] section, and the Poisson's ratios the chosen lattice can represent.

#include "latfrac/base/number_text.h"
#include "latfrac/geometry/lattice.h"
#include "latfrac/mechanics/random_calibration.h"
#include "problem_reader.h"

namespace latfrac::problem {
LatticeSpec read_lattice(const Section& top) {
  const Section s = top.required_section(
      "lattice", {"dim", "kind", "spacing", "size", "next_nearest", "seed", "mirror"});
  LatticeSpec lattice;
  if (!s.has("dim")) s.fail_missing("dim", "allowed: 2 (an x-z section) or 3");
  lattice.dim = static_cast<int>(*s.integer("dim", 2, 3));
  const bool flat = lattice.dim == 2;
  const std::string regular = flat ? "triangular" : "hcp";
  const std::string other = flat ? "hcp" : "triangular";
  const std::vector<std::string_view> kinds = {"triangular", "hcp", "random"};
  const int kind = s.choice("kind", kinds).value_or(flat ? 0 : 1);
  if (kinds[kind] == other) {
    s.fail("kind", "\"" + other + "\" is a " + (flat ? "3-D" : "2-D") + " lattice",
           "allowed with lattice.dim = " + std::to_string(lattice.dim) + ": \"" + regular +
               "\" (the default) or \"random\"");
  }
  lattice.kind = kinds[kind] == "random" ? LatticeKind::random : LatticeKind::regular;
  const bool random = lattice.kind == LatticeKind::random;
  lattice.spacing = s.required_number("spacing", positive("m"));

  const std::string shape = flat ? "[Lx, Lz] (lattice.dim = 2)" : "[Lx, Ly, Lz] (lattice.dim = 3)";
  if (!s.has("size")) s.fail_missing("size", "allowed: size = " + shape + " in m");
  const std::vector<double> size = *s.numbers("size", positive("m"), lattice.dim, shape);
  lattice.size = flat ? std::array{size[0], 0.0, size[1]} : std::array{size[0], size[1], size[2]};
  for (const double extent : size) {
    if (extent < 2 * lattice.spacing) {
      s.fail("size",
             "extent " + format_number(extent) + " m is less than 2 spacings of " +
                 format_number(lattice.spacing) + " m",
             "allowed: each extent >= 2 * lattice.spacing");
    }
    if (extent / lattice.spacing > max_spacings_per_axis) {
      s.fail("spacing",
             format_number(lattice.spacing) + " m puts " +
                 significant(extent / lattice.spacing, 3) + " spacings along an extent of " +
                 format_number(extent) + " m (no machine holds such a lattice, even with --force)",
             "allowed: at most " + format_number(max_spacings_per_axis) + " spacings per axis");
    }
  }

  // next_nearest = false is what these lattices have anyway: allowed, so that a 3-D HCP
  // problem can be run on a random lattice with --set lattice.next_nearest=false.
  if (s.has("next_nearest") && (flat || (random && s.boolean("next_nearest").value_or(false)))) {
    s.fail("next_nearest",
           flat ? "only applies in 3-D (the 2-D lattice has nearest-neighbour bonds only)"
                : "only applies to the \"hcp\" lattice (a random lattice's bonds are its "
                  "Delaunay edges)",
           flat ? "allowed: remove it, or set lattice.dim = 3"
                : "allowed: remove it, or set lattice.kind = \"hcp\"");
  }
  lattice.next_nearest = s.boolean("next_nearest").value_or(true);
  if (s.has("seed") && !random) {
    s.fail("seed", "only applies to a random lattice (lattice.kind = \"" + regular + "\")",
           "allowed: remove it, or set lattice.kind = \"random\"");
  }
  lattice.seed = static_cast<std::uint64_t>(
      s.integer("seed", 0, std::numeric_limits<std::int64_t>::max()).value_or(0));
  if (s.has("mirror") && !random) {
    s.fail("mirror", "only applies to a random lattice (a regular one is its own mirror image)",
           "allowed: remove it, or set lattice.kind = \"random\"");
  }
  lattice.mirror = s.boolean("mirror").value_or(false);
  return lattice;
}

Range poisson_range(const LatticeSpec& lattice) {
  if (lattice.kind == LatticeKind::random)
    return {0, random_lattice_max_poisson(lattice.dim), false, false, ""};
  return {-1, 0.25, true, false, ""};
}

std::string poisson_limit_reason(const LatticeSpec& lattice) {
  if (lattice.kind == LatticeKind::regular) {
    return "the lattice's shear springs would be negative (ks < 0), so nu must be at most 1/4";
  }
  return "a random " + std::to_string(lattice.dim) +
         "-D lattice reaches nu = " + format_number(random_lattice_max_poisson(lattice.dim)) +
         " with no shear springs (ks = 0) and nu = 0 with ks = kn, and no more "
         "(docs/model.md)";
}

}  // namespace latfrac::problem
