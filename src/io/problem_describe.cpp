// The resolved parameters of a scene as text, for `latfrac check` and the start of a run.
#include <cmath>
#include <iomanip>
#include <numbers>
#include <sstream>

#include "latfrac/io/problem_file.h"
#include "problem_reader.h"

namespace latfrac {
namespace {

using problem::format_number;

class Listing {
 public:
  void section(std::string_view title) { text_ << "[" << title << "]\n"; }
  void off(std::string_view title) { line(std::string("[").append(title).append("]"), "off", ""); }
  void top(std::string_view key, const std::string& value) { line(std::string(key), value, ""); }
  void entry(std::string_view key, const std::string& value, std::string_view unit = "") {
    line("  " + std::string(key), value, unit);
  }
  void entry(std::string_view key, double value, std::string_view unit = "") {
    entry(key, format_number(value), unit);
  }
  std::string str() const { return text_.str(); }

 private:
  void line(const std::string& key, const std::string& value, std::string_view unit) {
    text_ << key << std::string(key.size() < 26 ? 26 - key.size() : 1, ' ') << value;
    if (!unit.empty()) text_ << " " << unit;
    text_ << "\n";
  }
  std::ostringstream text_;
};

std::string on_off(bool value) { return value ? "true" : "false"; }

std::string point(const std::array<double, 3>& p, int dim) {
  std::string text = "[";
  text.append(format_number(p[0]));
  if (dim == 3) text.append(", ").append(format_number(p[1]));
  return text.append(", ").append(format_number(p[2])).append("]");
}

void describe_strength(const Strength& strength, Listing& out) {
  out.section("strength");
  out.entry("criterion", to_string(strength.criterion));
  out.entry("sigma0", strength.sigma0, "Pa");
  const bool uses_shear = strength.criterion != Criterion::tensile;
  if (strength.friction_angle) {
    out.entry("friction_angle", *strength.friction_angle,
              uses_shear ? "degrees" : "degrees (not used by this criterion)");
  } else {
    out.entry("friction_angle", "not given");
  }
  if (strength.tau0) {
    out.entry("tau0", *strength.tau0, uses_shear ? "Pa" : "Pa (not used by this criterion)");
  } else if (strength.friction_angle) {
    const double psi = *strength.friction_angle * std::numbers::pi / 180;
    const double tau0 =
        strength.tau0_factor * strength.sigma0 * (1 + std::sin(psi)) / (2 * std::cos(psi));
    std::ostringstream rounded;
    rounded << std::setprecision(6) << tau0;
    out.entry("tau0", rounded.str(),
              "Pa (derived: tau0_factor sigma0 (1 + sin psi) / (2 cos psi))");
  } else {
    out.entry("tau0", "not given (not used by this criterion)");
  }
  out.entry("tau0_factor", strength.tau0_factor);
  out.entry("bond_stress", to_string(strength.bond_stress),
            strength.criterion == Criterion::drucker_prager
                ? "(not used: drucker_prager always uses the stress tensor)"
            : strength.bond_stress == BondStress::strain ? "(sigma_n = E eps_n, tau = G gamma)"
            : strength.bond_stress == BondStress::tensor
                ? "(the bond's stress tensor resolved on its direction)"
                : "(the bond's stress tensor on the plane where f is largest)");
  out.entry(
      "internal_friction", strength.internal_friction,
      strength.criterion == Criterion::tensile || strength.criterion == Criterion::drucker_prager
          ? "(not used by this criterion)"
      : strength.internal_friction > 0 ? "(shear strength tau0 + mu_i <-sigma_n>+)"
                                       : "(shear strength tau0 in compression too)");
}

void describe_solver(const SolverOptions& solver, Listing& out) {
  const char* orderings[] = {"metis", "nesdis", "amd"};
  out.section("solver");
  out.entry("method", solver.method == EquilibriumMethod::newton ? "newton" : "relaxation");
  out.entry("backend", solver.backend == LinearBackendKind::cholmod ? "cholmod" : "petsc",
            solver.backend == LinearBackendKind::cholmod ? "(one CHOLMOD factor)"
                                                         : "(PETSc and MUMPS over the MPI ranks)");
  out.entry("tolerance", solver.tolerance, "(residual relative to the load)");
  out.entry("max_iterations", std::to_string(solver.max_iterations));
  out.entry("ordering", orderings[static_cast<int>(solver.ordering)]);
  out.entry("refactor_every", std::to_string(solver.refactor_every), "factor updates");
  out.entry("relaxation_omega", solver.relaxation_omega);
  out.entry("relaxation_tolerance", solver.relaxation_tolerance);
  out.entry("relaxation_max_sweeps", std::to_string(solver.relaxation_max_sweeps));
}

}  // namespace

std::string describe(const Scene& scene) {
  Listing out;
  const int dim = scene.lattice.dim;
  out.top("name", scene.name);
  if (!scene.description.empty()) out.top("description", scene.description);
  out.top("model", model_label(scene));
  if (!scene.source_path.empty()) out.top("source", scene.source_path);

  const LatticeSpec& lattice = scene.lattice;
  out.section("lattice");
  const bool random = lattice.kind == LatticeKind::random;
  out.entry("dim", std::to_string(dim), dim == 2 ? "(plane-strain x-z section)" : "(a block)");
  out.entry("kind", lattice_kind_name(dim, lattice.kind),
            random ? "(Poisson-disk points, Delaunay bonds)"
                   : (dim == 2 ? "(triangular)" : "(hexagonal close packed)"));
  out.entry("spacing", lattice.spacing, random ? "m (mean)" : "m");
  out.entry("size", point(lattice.size, dim), dim == 2 ? "m (x, z)" : "m (x, y, z)");
  out.entry("next_nearest", dim == 2 ? "not used in 2-D"
                            : random ? "not used by a random lattice"
                                     : on_off(lattice.next_nearest));
  out.entry("seed", random ? std::to_string(lattice.seed) : "not used by a regular lattice");
  out.entry("mirror", random ? on_off(lattice.mirror) : "not used by a regular lattice",
            random && lattice.mirror ? "(the points reflected in x)" : "");

  out.section("material");
  out.entry("density", scene.material.density, "kg/m^3");
  out.entry("young", scene.material.young, "Pa");
  out.entry("poisson", scene.material.poisson);

  out.section("boundary");
  for (int face = 0; face < face_count; ++face) {
    const bool y_face =
        face == static_cast<int>(Face::y_min) || face == static_cast<int>(Face::y_max);
    if (dim == 2 && y_face) continue;
    out.entry(to_string(static_cast<Face>(face)), to_string(scene.faces[face]));
  }

  if (scene.strength) {
    describe_strength(*scene.strength, out);
  } else {
    out.off("strength");
  }
  if (scene.gravity) {
    out.section("gravity");
    out.entry("g", scene.gravity->g, "m/s^2");
    out.entry("initial_stress",
              std::string(scene.gravity->lithostatic ? "lithostatic" : "elastic"));
    if (scene.gravity->lithostatic) {
      out.entry("stress_ratio", scene.gravity->stress_ratio, "(sigma0_h / sigma0_v)");
      out.entry("overburden", scene.gravity->overburden, "Pa (on the top face)");
    }
  } else {
    out.off("gravity");
  }

  out.section("loading");
  out.entry("mode", "extension");
  out.entry("total", scene.loading.total, "(strain; negative is compression)");
  if (scene.loading.basal_discontinuity) {
    out.entry("basal_discontinuity", *scene.loading.basal_discontinuity,
              "m (the base left of it moves with the left wall, right of it with the right)");
  }
  out.section("stepping");
  const bool fixed = scene.stepping.method == SteppingMethod::fixed;
  out.entry("method", fixed ? "fixed" : "event");
  out.entry("increment", fixed ? format_number(scene.stepping.increment) : "not used",
            fixed ? "(strain)" : "");

  if (scene.precuts.empty()) out.off("[precut]");
  for (const Precut& precut : scene.precuts) {
    out.section("[precut]");
    if (dim == 2) {
      out.entry("from", point(precut.from, 2), "m");
      out.entry("to", point(precut.to, 2), "m");
    } else {
      out.entry("corner", point(precut.corner, 3), "m");
      out.entry("edge1", point(precut.edge1, 3), "m");
      out.entry("edge2", point(precut.edge2, 3), "m");
    }
  }

  if (scene.contact) {
    out.section("contact");
    out.entry("enabled", "true");
    out.entry("friction", scene.contact->friction,
              scene.contact->friction > 0
                  ? "(dimensionless: Coulomb's mu on closed contacts, stick or slip at mu |Fn|)"
                  : "(dimensionless: 0, frictionless contacts)");
    if (scene.contact->friction > 0 && scene.lattice.dim == 3)
      out.entry("friction_facets", static_cast<double>(scene.contact->friction_facets),
                "(facets of the polygon inscribed in Coulomb's circle: strength between " +
                    format_number(std::cos(std::numbers::pi / scene.contact->friction_facets)) +
                    " mu |Fn| and mu |Fn| by direction)");
    out.entry("normal", scene.contact->normal == Contact::Normal::crack ? "crack" : "bond",
              scene.contact->normal == Contact::Normal::crack
                  ? "(a broken bond's contact acts across its crack's plane: a pre-cut's, or "
                    "the one its failure picks)"
                  : "(a broken bond's contact acts along the bond)");
  } else {
    out.off("contact");
  }

  if (scene.layers.empty()) out.off("[layer]");
  for (const Layer& layer : scene.layers) {
    out.section("[layer]");
    out.entry("z_min", layer.z_min, "m");
    out.entry("z_max", layer.z_max, "m");
    out.entry("density", layer.material.density, "kg/m^3");
    out.entry("young", layer.material.young, "Pa");
    out.entry("poisson", layer.material.poisson);
    out.entry("sigma0", layer.sigma0 ? format_number(*layer.sigma0) + " Pa" : "as [strength]");
    out.entry("tau0", layer.tau0 ? format_number(*layer.tau0) + " Pa" : "as [strength]");
  }

  if (scene.heterogeneity) {
    out.section("heterogeneity");
    out.entry("spread", scene.heterogeneity->spread);
    out.entry("seed", std::to_string(scene.heterogeneity->seed));
  } else {
    out.off("heterogeneity");
  }
  if (scene.large_kinematics) {
    out.section("large_kinematics");
    out.entry("enabled", "true");
  } else {
    out.off("large_kinematics");
  }

  out.section("output");
  std::string snapshots = "final state only";
  if (!scene.output.snapshots.empty()) {
    snapshots = "[";
    for (const double lambda : scene.output.snapshots) {
      snapshots += (snapshots.size() > 1 ? ", " : "") + format_number(lambda);
    }
    snapshots += "] (strain)";
  }
  out.entry("snapshots", snapshots);
  out.entry("exaggeration", scene.output.exaggeration);
  out.entry("picture", on_off(scene.output.picture));
  if (scene.output.picture) {
    const PictureOptions& picture = scene.output.picture_options;
    std::string shows =
        std::string(name_of(picture.view)) + ", " + std::string(name_of(picture.style));
    if (picture.field != NodeField::none) shows += ", field " + std::string(name_of(picture.field));
    if (picture.faults) shows += ", faults";
    if (picture.section_at)
      shows += std::string(picture.section_axis == SectionAxis::y ? ", y = " : ", x = ") +
               format_number(*picture.section_at) + " m";
    out.entry("picture_shows", shows + " (" + scene.output.picture_format + ", " +
                                   std::to_string(picture.width) + " px)");
  }

  describe_solver(scene.solver, out);
  return out.str();
}

}  // namespace latfrac
