// The sections of a problem file, read and checked against each other into a Scene.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <sstream>

#include "latfrac/criteria/criterion.h"
#include "latfrac/mechanics/friction_law.h"
#include "problem_reader.h"

namespace latfrac::problem {
namespace {

std::string coordinates(const std::array<double, 3>& point, int dim) {
  std::string text = "(";
  text.append(format_number(point[0]));
  if (dim == 3) text.append(", ").append(format_number(point[1]));
  return text.append(", ").append(format_number(point[2])).append(")");
}

std::string name_of(const std::string& text) { return "\"" + text + "\""; }

std::string read_name(const Section& top) {
  const std::string allowed =
      "allowed: letters, digits, '-', '_' and '.', e.g. name = \"graben-2d\"";
  if (!top.has("name")) top.fail_missing("name", allowed + " (it names the output files)");
  const std::string name = *top.string("name");
  const bool valid_characters = std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.';
  });
  // Output files add a suffix (".h5.partial", "-study.png") to the name, within the 255
  // bytes a file name can have.
  constexpr std::size_t longest = 200;
  if (name.size() > longest)
    top.fail("name",
             "is " + std::to_string(name.size()) + " characters long, too long to name files",
             "allowed: at most " + std::to_string(longest) + " characters");
  const bool only_dots = name.find_first_not_of('.') == std::string::npos;
  if (!valid_characters || only_dots) {
    top.fail("name", name_of(name) + " cannot name output files", allowed);
  }
  return name;
}

std::optional<double> read_poisson(const Section& s, const LatticeSpec& lattice) {
  const Range range = poisson_range(lattice);
  // Non-finite values are named with nu's own range, not the generic "a finite number".
  if (const toml::node* node = s.find("poisson"); node && node->is_floating_point()) {
    const double value = node->as_floating_point()->get();
    if (!std::isfinite(value)) {
      s.fail("poisson", "must be finite, got " + format_number(value),
             "allowed: " + range.describe("poisson"));
    }
  }
  const std::optional<double> nu = s.number("poisson", any_finite());
  if (nu && *nu > range.max) {
    s.fail("poisson", format_number(*nu) + " is too large: " + poisson_limit_reason(lattice),
           "allowed: " + range.describe("poisson"));
  }
  if (nu && *nu < range.min && lattice.kind == LatticeKind::random) {
    s.fail("poisson", format_number(*nu) + " is too small: " + poisson_limit_reason(lattice),
           "allowed: " + range.describe("poisson"));
  }
  return s.number("poisson", range);
}

Material read_material(const Section& top, const LatticeSpec& lattice) {
  const Section s = top.required_section("material", {"density", "young", "poisson"});
  Material material;
  material.density = s.required_number("density", positive("kg/m^3"));
  material.young = s.required_number("young", positive("Pa"));
  if (!s.has("poisson"))
    s.fail_missing("poisson", "allowed: " + poisson_range(lattice).describe("poisson"));
  material.poisson = *read_poisson(s, lattice);
  return material;
}

void read_boundary(const Section& top, int dim, Scene& scene) {
  const std::vector<std::string_view> faces = {"x_min", "x_max", "y_min",
                                               "y_max", "z_min", "z_max"};
  const std::optional<Section> s = top.section("boundary", faces);
  if (!s) return;
  for (int face = 0; face < face_count; ++face) {
    const bool y_face =
        face == static_cast<int>(Face::y_min) || face == static_cast<int>(Face::y_max);
    if (dim == 2 && y_face && s->has(faces[face])) {
      s->fail(faces[face], "a 2-D scene has no y faces (it is the x-z plane)",
              "allowed in 2-D: x_min, x_max, z_min, z_max");
    }
    const auto condition = s->choice(faces[face], {"free", "roller", "fixed", "extension"});
    if (condition) scene.faces[face] = static_cast<FaceCondition>(*condition);
  }
}

std::optional<Strength> read_strength(const Section& top) {
  const std::optional<Section> s =
      top.section("strength", {"criterion", "sigma0", "tau0", "friction_angle", "tau0_factor",
                               "bond_stress", "internal_friction"});
  if (!s) return std::nullopt;
  const std::vector<std::string_view> criteria(criterion_names().begin(), criterion_names().end());
  Strength strength;
  strength.criterion = static_cast<Criterion>(s->required_choice("criterion", criteria));
  strength.sigma0 = s->required_number("sigma0", positive("Pa"));
  strength.tau0 = s->number("tau0", positive("Pa"));
  strength.friction_angle = s->number("friction_angle", {0, 90, false, true, "degrees"});
  strength.tau0_factor = s->number("tau0_factor", positive(), 1.0);
  if (const auto source = s->choice("bond_stress", {"strain", "tensor", "critical_plane"}))
    strength.bond_stress = static_cast<BondStress>(*source);
  strength.internal_friction = s->number("internal_friction", non_negative(), 0.0);
  if (strength.internal_friction > 0 && strength.criterion == Criterion::elliptic &&
      strength.bond_stress == BondStress::critical_plane) {
    s->fail("internal_friction",
            "with criterion elliptic is not available on bond_stress = \"critical_plane\" (its "
            "largest value over planes has no convex form)",
            "allowed: bond_stress = \"tensor\" or \"strain\", or criterion tensile_or_shear");
  }
  if (strength.internal_friction > 0 && (strength.criterion == Criterion::tensile ||
                                         strength.criterion == Criterion::drucker_prager)) {
    s->fail("internal_friction",
            "is not used by criterion " + std::string(to_string(strength.criterion)) +
                " (tensile has no shear strength; drucker_prager has its own pressure term)",
            "allowed: 0, or criterion tensile_or_shear or elliptic");
  }

  const std::string criterion = name_of(to_string(strength.criterion));
  if (strength.tau0 && strength.tau0_factor != 1) {
    s->fail("tau0_factor",
            "cannot be combined with tau0: the factor only scales a tau0 derived "
            "from friction_angle",
            "allowed: tau0 alone, or friction_angle with tau0_factor");
  }
  if (needs_shear_strength(strength.criterion) && !strength.tau0 && !strength.friction_angle) {
    s->fail_missing("tau0", "criterion " + criterion +
                                " needs a shear strength: tau0 > 0 (Pa), "
                                "or friction_angle (degrees) to derive it");
  }
  // A derived tau0 beyond the doubles' range (tau0_factor or sigma0 near 1e308) would run
  // with an infinite shear strength and print "tau0 inf Pa": refused.
  if (!strength.tau0 && strength.friction_angle &&
      !std::isfinite(derived_tau0(strength.sigma0, *strength.friction_angle, strength.tau0_factor))) {
    const bool sigma0_alone = !std::isfinite(derived_tau0(strength.sigma0, *strength.friction_angle, 1.0));
    s->fail(sigma0_alone || !s->has("tau0_factor") ? "sigma0" : "tau0_factor",
            "gives a derived tau0 = tau0_factor sigma0 (1 + sin psi) / (2 cos psi) that is not "
            "finite (tau0_factor " + format_number(strength.tau0_factor) + ", sigma0 " +
                format_number(strength.sigma0) + " Pa)",
            "allowed: tau0_factor and sigma0 whose derived tau0 is finite");
  }
  if (needs_friction_angle(strength.criterion) && !strength.friction_angle) {
    s->fail_missing("friction_angle",
                    "criterion " + criterion + " needs " +
                        Range{0, 90, false, true, "degrees"}.describe("friction_angle"));
  }
  return strength;
}

Precut read_precut(const Section& s, const LatticeSpec& lattice) {
  const bool flat = lattice.dim == 2;
  const std::vector<std::string_view> foreign =
      flat ? std::vector<std::string_view>{"corner", "edge1", "edge2"}
           : std::vector<std::string_view>{"from", "to"};
  const std::string allowed = flat ? "allowed in 2-D: from = [x, z] and to = [x, z] (m)"
                                   : "allowed in 3-D: corner, edge1, edge2 = [x, y, z] (m)";
  for (const std::string_view key : foreign) {
    if (s.has(key)) s.fail(key, "is a " + std::string(flat ? "3-D" : "2-D") + " key", allowed);
  }
  const auto point = [&](std::string_view key) {
    const std::string shape = flat ? "[x, z]" : "[x, y, z]";
    if (!s.has(key)) s.fail_missing(key, allowed);
    const std::vector<double> v = *s.numbers(key, any_finite("m"), lattice.dim, shape);
    return flat ? std::array{v[0], 0.0, v[1]} : std::array{v[0], v[1], v[2]};
  };
  const auto check_inside = [&](std::string_view key, std::string_view what,
                                const std::array<double, 3>& p) {
    bool inside = true;
    std::string box;
    for (int axis = 0; axis < 3; ++axis) {
      if (flat && axis == 1) continue;
      if (!box.empty()) box += ", ";
      box += "0 <= " + std::string(1, "xyz"[axis]) + " <= " + format_number(lattice.size[axis]);
      inside =
          inside && p[axis] >= -lattice.spacing && p[axis] <= lattice.size[axis] + lattice.spacing;
    }
    if (!inside) {
      s.fail(key, std::string(what) + " " + coordinates(p, lattice.dim) + " lies outside the box",
             "allowed: " + box + " (m), give or take one spacing");
    }
  };

  Precut precut;
  if (flat) {
    precut.from = point("from");
    precut.to = point("to");
    check_inside("from", "point", precut.from);
    check_inside("to", "point", precut.to);
    if (precut.from == precut.to)
      s.fail("to", "equals from", "allowed: a segment of non-zero length");
    return precut;
  }
  precut.corner = point("corner");
  precut.edge1 = point("edge1");
  precut.edge2 = point("edge2");
  const std::array<double, 3>& a = precut.corner;
  const std::array<double, 3>& b = precut.edge1;
  const std::array<double, 3>& c = precut.edge2;
  const double length1 = std::hypot(b[0], b[1], b[2]);
  const double length2 = std::hypot(c[0], c[1], c[2]);
  if (length1 == 0) s.fail("edge1", "is zero", "allowed: a non-zero edge vector");
  if (length2 == 0) s.fail("edge2", "is zero", "allowed: a non-zero edge vector");
  const double cross =
      std::hypot(b[1] * c[2] - b[2] * c[1], b[2] * c[0] - b[0] * c[2], b[0] * c[1] - b[1] * c[0]);
  if (cross <= 1e-9 * length1 * length2) {
    s.fail("edge2", "is parallel to edge1", "allowed: two edges that span a rectangle");
  }
  const auto plus = [](std::array<double, 3> p, const std::array<double, 3>& q) {
    for (int axis = 0; axis < 3; ++axis) p[axis] += q[axis];
    return p;
  };
  check_inside("corner", "corner", a);
  check_inside("edge1", "corner + edge1", plus(a, b));
  check_inside("edge2", "corner + edge2", plus(a, c));
  check_inside("edge2", "corner + edge1 + edge2", plus(plus(a, b), c));
  return precut;
}

std::vector<Layer> read_layers(const Section& top, const Scene& scene) {
  const std::vector<Section> entries =
      top.sections("layer", {"z_min", "z_max", "density", "young", "poisson", "sigma0", "tau0"});
  std::vector<Layer> layers;
  for (const Section& s : entries) {
    Layer layer;
    layer.z_min = s.required_number("z_min", non_negative("m"));
    layer.z_max = s.required_number("z_max", positive("m"));
    if (layer.z_max <= layer.z_min) {
      s.fail("z_max", "must be above z_min = " + format_number(layer.z_min) + " m",
             "allowed: 0 <= z_min < z_max");
    }
    if (layer.z_min >= scene.lattice.size[2]) {
      s.fail("z_min",
             "lies above the box (its height is " + format_number(scene.lattice.size[2]) + " m)",
             "allowed: 0 <= z_min < box height");
    }
    layer.material = scene.material;
    layer.material.density = s.number("density", positive("kg/m^3"), scene.material.density);
    layer.material.young = s.number("young", positive("Pa"), scene.material.young);
    layer.material.poisson = read_poisson(s, scene.lattice).value_or(scene.material.poisson);
    layer.sigma0 = s.number("sigma0", positive("Pa"));
    layer.tau0 = s.number("tau0", positive("Pa"));
    for (const std::string_view key : {"sigma0", "tau0"}) {
      if (s.has(key) && !scene.strength) {
        s.fail(key, "has no effect: the scene has no [strength] section",
               "allowed: add [strength], or remove the key");
      }
    }
    for (std::size_t i = 0; i < layers.size(); ++i) {
      if (layer.z_min < layers[i].z_max && layers[i].z_min < layer.z_max) {
        s.fail("z_min",
               "the layer from " + format_number(layer.z_min) + " to " +
                   format_number(layer.z_max) + " m overlaps layer[" + std::to_string(i) +
                   "] from " + format_number(layers[i].z_min) + " to " +
                   format_number(layers[i].z_max) + " m",
               "allowed: layers that do not overlap");
      }
    }
    layers.push_back(layer);
  }
  return layers;
}

void read_effects(const Section& top, Scene& scene) {
  if (const auto s =
          top.section("gravity", {"g", "initial_stress", "stress_ratio", "overburden"})) {
    scene.gravity = Gravity{s->number("g", non_negative("m/s^2"), 9.81)};
    scene.gravity->lithostatic =
        s->choice("initial_stress", {"elastic", "lithostatic"}).value_or(0) == 1;
    if (scene.gravity->lithostatic && scene.lattice.kind != LatticeKind::random) {
      s->fail("initial_stress",
              std::string("\"lithostatic\" on a ") +
                  lattice_kind_name(scene.lattice.dim, scene.lattice.kind) +
                  " lattice (a bond's prestress is its Voronoi facet's share of the stress)",
              "allowed: \"lithostatic\" with lattice.kind = \"random\", or \"elastic\"");
    }
    // K of the crust lies between about 0.2 and a few (larger near the surface); beyond 100
    // the prestress dwarfs gravity and the runs fail or fly apart (K = 1e4: 524 km).
    if (const auto ratio = s->number("stress_ratio", {0, 100, false, false, ""})) {
      if (!scene.gravity->lithostatic)
        s->fail("stress_ratio",
                "has no effect: the elastic start's horizontal stress is gravity's "
                "nu / (1 - nu) sigma_zz",
                "allowed: gravity.initial_stress = \"lithostatic\", or remove stress_ratio");
      scene.gravity->stress_ratio = *ratio;
    }
    if (const auto overburden = s->number("overburden", non_negative("Pa"))) {
      if (!scene.gravity->lithostatic)
        s->fail("overburden",
                "needs the lithostatic start (the top's pressure is balanced by the bonds' "
                "initial stress)",
                "allowed: gravity.initial_stress = \"lithostatic\", or remove overburden");
      scene.gravity->overburden = *overburden;
    }
  }
  if (const auto s = top.section("contact", {"enabled", "friction", "friction_facets", "normal"})) {
    // At most 100: a friction angle of 89.4 deg, stick under any practical load. Far above
    // it the solves fail: on the complete 2-D scene at 3000 m, mu = 1e4 ran, mu = 1e8 ended
    // at lambda 8.4e-4 with a residual of 1.3e-9 of the load after a fresh factorization.
    const double friction = s->number("friction", {0, 100, false, false, ""}, 0.0);
    const auto facets = s->integer("friction_facets", 3, FrictionalContactLaw::max_facets);
    if (s->boolean("enabled").value_or(true)) {
      scene.contact = Contact{true, friction};
    } else if (friction > 0) {
      s->fail("friction",
              "has no effect: contact.enabled is false (friction acts on closed contacts)",
              "allowed: contact.enabled = true, or remove friction");
    }
    if (facets) {
      if (scene.lattice.dim == 2)
        s->fail("friction_facets",
                "has no effect in 2-D (the friction cone of a 2-D contact is exact: two senses of "
                "slip)",
                "allowed: friction_facets in a 3-D scene (lattice.dim = 3)");
      if (!(friction > 0))
        s->fail("friction_facets", "has no effect without friction (contact.friction is 0)",
                "allowed: contact.friction > 0, or remove friction_facets");
      scene.contact->friction_facets = static_cast<int>(*facets);
    }
    if (const auto normal = s->choice("normal", {"bond", "crack"})) {
      if (!scene.contact)
        s->fail("normal", "has no effect: contact.enabled is false",
                "allowed: contact.enabled = true, or remove normal");
      scene.contact->normal = static_cast<Contact::Normal>(*normal);
    }
  }
  if (const auto s = top.section("large_kinematics", {"enabled"})) {
    scene.large_kinematics = s->boolean("enabled").value_or(true);
    if (scene.large_kinematics && scene.gravity && scene.gravity->lithostatic)
      s->fail("enabled",
              "large kinematics with gravity.initial_stress = \"lithostatic\" (a prestretch "
              "along the bond's reference direction is a small-kinematics notion)",
              "allowed: large_kinematics.enabled = false, or gravity.initial_stress = \"elastic\"");
  }
  if (const auto s = top.section("heterogeneity", {"spread", "seed"})) {
    Heterogeneity heterogeneity;
    heterogeneity.spread = s->required_number("spread", {0, 1, false, true, ""});
    heterogeneity.seed =
        s->integer("seed", 0, std::numeric_limits<std::int64_t>::max()).value_or(0);
    if (!scene.strength) {
      s->fail("spread", "has no effect: the scene has no [strength] section",
              "allowed: add [strength], or remove [heterogeneity]");
    }
    scene.heterogeneity = heterogeneity;
  }
}

void read_loading(const Section& top, Scene& scene) {
  if (const auto s = top.section("loading", {"mode", "total", "basal_discontinuity"})) {
    s->choice("mode", {"extension"});
    scene.loading.total = s->number("total", {-0.5, 0.5, false, false, "strain"}, 0.0);
    const double length = scene.lattice.size[0];
    scene.loading.basal_discontinuity =
        s->number("basal_discontinuity", {0, length, true, true, "m"});
  }
  if (const auto s = top.section("stepping", {"method", "increment"})) {
    scene.stepping.method =
        static_cast<SteppingMethod>(s->choice("method", {"event", "fixed"}).value_or(0));
    const std::optional<double> increment = s->number("increment", positive("strain"));
    if (scene.stepping.method == SteppingMethod::fixed && !increment) {
      s->fail_missing("increment", "method \"fixed\" needs increment > 0 (strain), e.g. 1e-3");
    }
    scene.stepping.increment = increment.value_or(0);
    // The bound run_scene checks too (schedule.h), here with the file's line.
    if (scene.stepping.method == SteppingMethod::fixed &&
        std::abs(scene.loading.total) / *increment > max_fixed_steps) {
      std::ostringstream steps;
      steps << std::abs(scene.loading.total) / *increment << " fixed steps to loading.total = "
            << scene.loading.total;
      s->fail("increment", "makes " + steps.str(),
              "allowed: at most 1e9 steps (increment >= |loading.total| / 1e9)");
    }
  }
}

void read_solver(const Section& top, SolverOptions& solver) {
  const auto s = top.section(
      "solver", {"method", "backend", "tolerance", "max_iterations", "ordering", "refactor_every",
                 "relaxation_omega", "relaxation_tolerance", "relaxation_max_sweeps"});
  if (!s) return;
  const std::int64_t int_max = std::numeric_limits<int>::max();
  solver.method =
      static_cast<EquilibriumMethod>(s->choice("method", {"newton", "relaxation"}).value_or(0));
  solver.backend =
      static_cast<LinearBackendKind>(s->choice("backend", {"cholmod", "petsc"}).value_or(0));
  // A relative residual below 1e-15 is below double precision's rounding of the load: no
  // factor reaches it, and every solve would end in the ill-conditioning error.
  const Range reachable{1e-15, 1, false, true, ""};
  solver.tolerance = s->number("tolerance", reachable, solver.tolerance);
  solver.max_iterations =
      static_cast<int>(s->integer("max_iterations", 1, int_max).value_or(solver.max_iterations));
  solver.ordering =
      static_cast<Ordering>(s->choice("ordering", {"metis", "nesdis", "amd"}).value_or(0));
  solver.refactor_every =
      static_cast<int>(s->integer("refactor_every", 1, int_max).value_or(solver.refactor_every));
  solver.relaxation_omega =
      s->number("relaxation_omega", {0, 2, true, true, ""}, solver.relaxation_omega);
  solver.relaxation_tolerance =
      s->number("relaxation_tolerance", reachable, solver.relaxation_tolerance);
  solver.relaxation_max_sweeps =
      static_cast<long>(s->integer("relaxation_max_sweeps", 1, std::numeric_limits<long>::max())
                            .value_or(solver.relaxation_max_sweeps));
}

}  // namespace

Scene read_scene(const Origin& origin, const toml::table& root) {
  const Section top(origin, root, "", "the top level",
                    {"name", "description", "lattice", "material", "boundary", "strength",
                     "gravity", "loading", "stepping", "precut", "contact", "layer",
                     "heterogeneity", "large_kinematics", "output", "solver"});
  Scene scene;
  scene.name = read_name(top);
  scene.description = top.string("description").value_or("");
  scene.lattice = read_lattice(top);
  scene.material = read_material(top, scene.lattice);
  read_boundary(top, scene.lattice.dim, scene);
  scene.strength = read_strength(top);
  read_effects(top, scene);
  read_loading(top, scene);
  for (const Section& s : top.sections("precut", {"from", "to", "corner", "edge1", "edge2"})) {
    scene.precuts.push_back(read_precut(s, scene.lattice));
  }
  scene.layers = read_layers(top, scene);
  read_output(top, scene);
  read_solver(top, scene.solver);
  return scene;
}

}  // namespace latfrac::problem
