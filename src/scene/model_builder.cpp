// Builds the mechanical model of a scene: lattice, springs, strengths, supports, gravity.
#include "latfrac/scene/model_builder.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <string_view>

#include "latfrac/base/error.h"
#include "latfrac/criteria/criterion.h"
#include "latfrac/geometry/precut.h"
#include "latfrac/mechanics/calibration.h"
#include "latfrac/mechanics/random_calibration.h"

namespace latfrac {
namespace {

// The layer holding height z. The lattice's top row can lie above the requested height
// (the box is filled with whole row pitches), so a layer that reaches the requested top
// also holds everything above it.
const Layer* layer_at(const Scene& scene, double z) {
  const double top = scene.lattice.size[2];
  for (const Layer& layer : scene.layers) {
    const bool reaches_top = layer.z_max >= top * (1 - 1e-12);
    if (z >= layer.z_min && (z < layer.z_max || reaches_top)) return &layer;
  }
  return nullptr;
}

const Material& material_at(const Scene& scene, double z) {
  const Layer* layer = layer_at(scene, z);
  return layer ? layer->material : scene.material;
}

// The friction angle of a crack's Coulomb plane (crack_plane.h), radians: the bonds'
// internal friction where they have it, else the criterion's psi, else 0 (45 degrees).
double crack_friction_angle(const Scene& scene) {
  if (!scene.strength) return 0;
  if (scene.strength->internal_friction > 0) return std::atan(scene.strength->internal_friction);
  if (scene.strength->friction_angle)
    return *scene.strength->friction_angle * std::numbers::pi / 180;
  return 0;
}

// A frictional contact sticks on the broken bond's own shear spring (docs/model.md,
// "Friction on closed contacts"); where ks = 0 its tangential force stays 0, so friction
// would silently do nothing. That is the largest Poisson's ratio a lattice has: 1/4 on the
// regular ones, random_lattice_max_poisson on random ones.
void check_stick_springs(const Scene& scene, const Model& model) {
  const Lattice& lattice = model.lattice;
  for (std::int64_t b = 0; b < lattice.bond_count(); ++b) {
    if (lattice.bonds[b].kind == BondKind::next_nearest || model.shear_stiffness[b] > 0 ||
        !(model.normal_stiffness[b] > 0))
      continue;
    const double mid_z = 0.5 * (lattice.positions[lattice.bonds[b].i].z() +
                                lattice.positions[lattice.bonds[b].j].z());
    const Layer* layer = layer_at(scene, mid_z);
    const Material& material = layer ? layer->material : scene.material;
    std::ostringstream message;
    message << "contact.friction: " << scene.contact->friction
            << " acts through the broken bonds' shear springs, and ";
    if (layer)
      message << "the [[layer]] from z = " << layer->z_min << " to " << layer->z_max
              << " m with poisson = " << material.poisson;
    else
      message << "material.poisson = " << material.poisson;
    message << " leaves none (ks = 0 at the largest nu of a "
            << (lattice.is_random() ? "random" : "regular") << " " << lattice.dim << "-D lattice, "
            << (lattice.is_random() ? random_lattice_max_poisson(lattice.dim) : 0.25)
            << "), so contacts could not stick; allowed: a smaller poisson, or "
               "contact.friction = 0";
    throw InputError(message.str());
  }
}

// Moduli and strengths per bond: the layer holding the bond's midpoint, times a random
// factor uniform in [1 - spread, 1 + spread] when the scene names heterogeneity.
void assign_strengths(const Scene& scene, const FailureCriterion* criterion, Model& model) {
  const Lattice& lattice = model.lattice;
  const std::int64_t bonds = lattice.bond_count();
  model.bond_young.resize(bonds);
  model.bond_shear_modulus.resize(bonds);
  model.bond_sigma0.assign(bonds, 0.0);
  model.bond_tau0.assign(bonds, 0.0);
  std::mt19937_64 generator(scene.heterogeneity ? scene.heterogeneity->seed : 0);
  const double spread = scene.heterogeneity ? scene.heterogeneity->spread : 0.0;
  std::uniform_real_distribution<double> factor(1 - spread, 1 + spread);
  for (std::int64_t b = 0; b < bonds; ++b) {
    const Bond& bond = lattice.bonds[b];
    const double mid_z = 0.5 * (lattice.positions[bond.i].z() + lattice.positions[bond.j].z());
    const Layer* layer = layer_at(scene, mid_z);
    const Material& material = layer ? layer->material : scene.material;
    model.bond_young[b] = material.young;
    model.bond_shear_modulus[b] = material.young / (2 * (1 + material.poisson));
    if (!criterion) continue;
    const double scale = spread > 0 ? factor(generator) : 1.0;
    const CriterionParameters& resolved = criterion->parameters();
    const double sigma0 = layer && layer->sigma0 ? *layer->sigma0 : resolved.sigma0;
    double tau0 = layer && layer->tau0 ? *layer->tau0 : resolved.tau0;
    // A layer that sets its own sigma0 but not tau0 scales a derived tau0 with it.
    if (layer && layer->sigma0 && !layer->tau0 && !scene.strength->tau0)
      tau0 *= sigma0 / resolved.sigma0;
    model.bond_sigma0[b] = scale * sigma0;
    model.bond_tau0[b] = scale * tau0;
  }
}

// The failure indices are squares of stress over strength. A strength below 1e-12 of the
// modulus (a failure strain that no rock has) makes f overflow to inf under any loading:
// refused with the values, before any solve.
// A criterion without a shear strength (tensile, with neither tau0 nor friction_angle)
// gives every bond tau0 = inf, meaning none: only a finite resolved tau0 is checked.
void check_failure_strains(const Model& model, bool has_shear_strength) {
  constexpr double smallest_failure_strain = 1e-12;
  std::ostringstream message;
  for (std::int64_t b = 0; b < model.lattice.bond_count(); ++b) {
    for (const auto& [name, strength] :
         {std::pair{"sigma0", model.bond_sigma0[b]}, std::pair{"tau0", model.bond_tau0[b]}}) {
      if (!has_shear_strength && std::string_view(name) == "tau0") continue;
      if (!std::isfinite(strength)) {
        // A layer's sigma0 near 1e308 scales a derived tau0 past the doubles' range.
        message << "strength." << name << " of bond " << b
                << " is not finite (a layer's sigma0 scales the derived tau0 by its ratio to "
                   "strength.sigma0); allowed: strengths whose values stay finite";
        throw InputError(message.str());
      }
      if (!(strength > 0) || strength >= smallest_failure_strain * model.bond_young[b]) continue;
      message << "strength." << name << " = " << strength
              << " Pa against young = " << model.bond_young[b] << " Pa (bond " << b
              << ") is a failure strain below 1e-12, which makes the failure index overflow; "
                 "allowed: strengths of at least 1e-12 times the Young modulus";
      throw InputError(message.str());
    }
  }
}

// The lithostatic stress at height z, Pa (compression negative): -g times the integral of
// the density from z to the lattice's top, over the layers each height lies in.
double lithostatic_stress(const Scene& scene, double g, double top, double z) {
  std::vector<double> cuts{z, top};
  for (const Layer& layer : scene.layers)
    for (double c : {layer.z_min, layer.z_max})
      if (c > z && c < top) cuts.push_back(c);
  std::sort(cuts.begin(), cuts.end());
  double weight = 0;  // Pa per (m/s^2)
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k)
    weight += material_at(scene, 0.5 * (cuts[k] + cuts[k + 1])).density * (cuts[k + 1] - cuts[k]);
  return -g * weight;
}

// The traction sigma0 n A on a facet (area A, unit normal n) of the initial stress
// sigma0 = vertical diag(K, K, 1) (2-D: diag(K, 1) in x-z).
Vec3 initial_traction(double vertical, double ratio, const Vec3& n, double area) {
  return {ratio * vertical * n.x() * area, ratio * vertical * n.y() * area,
          vertical * n.z() * area};
}

// Gravity's strain at the base, (rho g H + p0) / E with E the softest material's modulus,
// is bounded by 1e12, as failure strains are from below (check_failure_strains): the
// displacements, about that strain times H, then stay far inside the doubles' range. A
// young of 1e-300 Pa made them overflow (NaN in the first solve, with an error about
// conditioning that named no key). The crust's is about 0.008 (2600 kg/m^3, 9.81 m/s^2,
// 30 km, 100 GPa); a soft layer of 1e7 Pa under 8 km has 20 and runs (hard-case tests).
void check_gravity_strain(const Scene& scene, double top) {
  constexpr double largest_gravity_strain = 1e12;
  const double base_stress =
      -lithostatic_stress(scene, scene.gravity->g, top, 0.0) + scene.gravity->overburden;
  double softest = scene.material.young;
  for (const Layer& layer : scene.layers) softest = std::min(softest, layer.material.young);
  const double strain = base_stress / softest;
  if (std::abs(strain) <= largest_gravity_strain) return;
  std::ostringstream message;
  message << "gravity's stress at the base, " << base_stress << " Pa (material.density = "
          << scene.material.density << " kg/m^3" << (scene.layers.empty() ? "" : " and the layers'")
          << ", gravity.g = " << scene.gravity->g
          << " m/s^2 over the height, plus gravity.overburden), against material.young = "
          << softest << " Pa" << (scene.layers.empty() ? "" : " (the softest layer's)")
          << " is a strain of " << strain
          << ", which makes the displacements overflow; allowed: strains rho g H / E up to "
             "1e12 (the crust's is about 0.008)";
  throw InputError(message.str());
}

// The initial stress (docs/model.md, "Initial stress"): sigma0 = sigma0_v(z) diag(K, K, 1)
// (2-D: diag(K, 1) in x-z), sigma0_v = -p0 - the lithostatic stress of the lattice itself
// (p0 the overburden). Bond b carries its Voronoi facet's traction t0 = sigma0(c_b) n0 A_b
// (area A_b, centroid c_b, normal n0) at zero displacement: its springs are already
// displaced by d_b = -(t0.n0 / kn) n0 - t0_s / ks, t0_s the traction's part across n0.
// Summed over a node's facets these forces are the divergence of sigma0 over its cell
// (sigma0 is linear in z there), rho g V upwards: its weight; sigma0's horizontal part
// does not vary along x and adds nothing.
void set_lithostatic_prestress(const Scene& scene, Model& model) {
  const Lattice& lattice = model.lattice;
  const double g = scene.gravity->g;
  const double ratio = scene.gravity->stress_ratio;
  const double overburden = scene.gravity->overburden;
  const double top = lattice.extent.z();
  model.prestretch.resize(lattice.bond_count());
  for (std::int64_t b = 0; b < lattice.bond_count(); ++b) {
    const double vertical =
        lithostatic_stress(scene, g, top, lattice.bond_facet_centroid[b].z()) - overburden;
    const Vec3& n = lattice.bond_direction[b];
    const double area = lattice.bond_facet_area[b];
    if (ratio == 1) {
      // The isotropic state: t0 = sigma0 A along n0 exactly (no rounding shear, so bonds
      // without shear springs carry it), delta_b = -sigma0 A / kn.
      model.prestretch[b] = (-vertical * area / model.normal_stiffness[b]) * n;
      continue;
    }
    const Vec3 traction = initial_traction(vertical, ratio, n, area);
    const double normal = traction.dot(n);
    const Vec3 shear = traction - normal * n;
    Vec3 d = -(normal / model.normal_stiffness[b]) * n;
    if (shear.norm() > 0) {
      if (!(model.shear_stiffness[b] > 0))
        throw InputError("gravity.stress_ratio != 1 needs shear springs (bond " +
                         std::to_string(b) +
                         " has ks = 0): an anisotropic initial stress shears the bonds");
      d -= shear / model.shear_stiffness[b];
    }
    model.prestretch[b] = d;
  }
  model.initial_stress_ratio = ratio;
  model.node_initial_stress.resize(lattice.node_count());
  for (std::int64_t n = 0; n < lattice.node_count(); ++n)
    model.node_initial_stress[n] =
        lithostatic_stress(scene, g, top, lattice.positions[n].z()) - overburden;
}

// The overburden p0 pushes on the top face: each top face piece (the part of the top that
// closes a node's Voronoi cell, area A) carries -p0 A e_z. With the initial stress's
// uniform part, -p0 diag(K, K, 1), the top nodes then stand still as the others do. A top
// node held along z hands its share to its support.
void add_overburden_load(const Scene& scene, Model& model) {
  model.top_pressure = scene.gravity->overburden;
  if (model.top_pressure == 0) return;
  const Lattice& lattice = model.lattice;
  const int dim = lattice.dim;
  for (const FacePiece& piece : lattice.face_pieces) {
    if (!lattice.on_top(piece)) continue;
    const std::int64_t dof = piece.node * dim + (dim - 1);
    if (model.dofs().free_index[dof] >= 0)
      model.external_force[dof] -= model.top_pressure * piece.area;
  }
}

}  // namespace

Model build_model(const Scene& scene) {
  if (!scene.strength) return build_model(scene, nullptr);
  return build_model(scene, make_criterion(*scene.strength, scene.lattice.dim).get());
}

Model build_model(const Scene& scene, const FailureCriterion* criterion) {
  const LatticeSpec& spec = scene.lattice;
  validate_material(scene.material, spec.dim, spec.kind);
  for (const Layer& layer : scene.layers)
    validate_material(layer.material, spec.dim, spec.kind, "layer");
  Model model;
  model.lattice = build_lattice(spec);
  const Lattice& lattice = model.lattice;
  const int dim = lattice.dim;

  const std::int64_t bonds = lattice.bond_count();
  model.normal_stiffness.resize(bonds);
  model.shear_stiffness.resize(bonds);
  ModelEditor editor(model);
  editor.reset_states();
  // A random lattice's (En, alpha), once per material (the scene's and each layer's).
  std::vector<std::pair<const Material*, RandomSpringParameters>> random_springs;
  const auto random_springs_of = [&](const Material& material) {
    for (const auto& [known, parameters] : random_springs)
      if (known == &material) return parameters;
    random_springs.emplace_back(&material, random_spring_parameters(dim, material));
    return random_springs.back().second;
  };
  for (std::int64_t b = 0; b < bonds; ++b) {
    const Bond& bond = lattice.bonds[b];
    const double mid_z = 0.5 * (lattice.positions[bond.i].z() + lattice.positions[bond.j].z());
    const Material& material = material_at(scene, mid_z);
    if (lattice.is_random()) {
      // kn = En A / L, ks = alpha kn (random_calibration.h).
      const RandomSpringParameters p = random_springs_of(material);
      model.normal_stiffness[b] =
          p.normal_modulus * lattice.bond_facet_area[b] / lattice.bond_length[b];
      model.shear_stiffness[b] = p.shear_ratio * model.normal_stiffness[b];
      continue;
    }
    const SpringConstants k = spring_constants(dim, material, lattice.spacing);
    const double scale = bond.kind == BondKind::next_nearest ? next_nearest_fraction : 1.0;
    model.normal_stiffness[b] = scale * k.normal;
    model.shear_stiffness[b] = scale * k.shear;
  }

  if (scene.contact && scene.contact->friction > 0) check_stick_springs(scene, model);
  assign_strengths(scene, criterion, model);
  check_failure_strains(model, criterion && std::isfinite(criterion->parameters().tau0));
  model.precut.assign(bonds, 0);
  for (std::int64_t b : bonds_crossing_precuts(lattice, scene.precuts)) {
    model.precut[b] = 1;
    editor.set_state(b, PairState::open);
  }
  if (scene.contact && scene.contact->normal == Contact::Normal::crack) {
    model.contact_normal = lattice.bond_direction;
    model.crack_friction_angle = crack_friction_angle(scene);
    for (const Precut& cut : scene.precuts) {
      const Vec3 n = precut_normal(cut, dim);
      for (std::int64_t b : bonds_crossing_precuts(lattice, {cut}))
        model.contact_normal[b] = n.dot(lattice.bond_direction[b]) >= 0 ? n : Vec3(-n);
    }
  }

  editor.set_dofs(build_dof_map(lattice, scene.faces, scene.loading.basal_discontinuity));
  model.external_force = Vector::Zero(model.dofs().dof_count());
  model.node_poisson.resize(lattice.node_count());
  for (std::int64_t n = 0; n < lattice.node_count(); ++n) {
    const Material& material = material_at(scene, lattice.positions[n].z());
    model.node_poisson[n] = material.poisson;
    if (scene.gravity) {
      const int z_component = dim - 1;
      model.external_force[n * dim + z_component] =
          -material.density * scene.gravity->g * lattice.volume_of(n);
    }
  }
  // Subnormal weights (below 2.2e-308 N, density or g near 5e-324) lose their precision:
  // the first solve then missed its residual by the whole load, with advice about the
  // tolerance that could not help. Weights that underflow to 0 are gravity off, and fine.
  if (scene.gravity) {
    for (Eigen::Index k = 0; k < model.external_force.size(); ++k) {
      const double w = std::abs(model.external_force[k]);
      if (w > 0 && w < std::numeric_limits<double>::min()) {
        std::ostringstream message;
        message << "gravity.g = " << scene.gravity->g
                << " m/s^2 and the densities (material.density = " << scene.material.density
                << " kg/m^3) give nodes' weights of " << w
                << " N, subnormal numbers that keep too few digits to solve with; allowed: "
                   "weights above 2.2e-308 N (any physical density and g), or no [gravity]";
        throw InputError(message.str());
      }
    }
  }
  if (scene.gravity && !std::isfinite(model.external_force.squaredNorm())) {
    // A weight beyond the doubles' range would carry inf, then NaN, into every solve; so
    // would weights whose squares overflow in the residual's norm (a density of 1e300
    // kg/m^3 failed in the first solve with a conditioning error that named no key).
    // Name the density that did it: the scene's, or the densest layer's.
    std::string density_key = "material.density";
    double density = scene.material.density;
    for (const Layer& layer : scene.layers) {
      if (layer.material.density > density) {
        density = layer.material.density;
        std::ostringstream key;
        key << "the density of the [[layer]] from z = " << layer.z_min << " to " << layer.z_max
            << " m";
        density_key = key.str();
      }
    }
    std::ostringstream message;
    message << "gravity.g = " << scene.gravity->g << " m/s^2 and " << density_key << " = "
            << density
            << " kg/m^3 give nodes' weights whose squares are not finite numbers (density "
               "times g times a node's volume overflows); allowed: weights that are finite "
               "when squared, as any physical density's and g's are";
    throw InputError(message.str());
  }
  if (scene.gravity) check_gravity_strain(scene, lattice.extent.z());
  if (scene.gravity && scene.gravity->overburden != 0 && !scene.gravity->lithostatic)
    throw InputError("gravity.overburden needs gravity.initial_stress = \"lithostatic\"");
  if (scene.gravity && scene.gravity->lithostatic) {
    if (!lattice.is_random() || scene.large_kinematics)
      throw InputError(
          "gravity.initial_stress = \"lithostatic\" needs a random lattice and small kinematics");
    set_lithostatic_prestress(scene, model);
    add_overburden_load(scene, model);
  }
  std::unique_ptr<BondLaw> bond_law;
  if (scene.large_kinematics) {
    bond_law = std::make_unique<LargeKinematics>(dim);
  } else {
    bond_law = std::make_unique<SmallKinematics>(dim);
  }
  std::unique_ptr<InteractionLaw> contact_law;
  if (scene.contact && scene.contact->friction > 0) {
    contact_law = std::make_unique<FrictionalContactLaw>(
        lattice.spacing, scene.contact->friction, dim == 3 ? scene.contact->friction_facets : 0);
  } else if (scene.contact) {
    contact_law = std::make_unique<ContactLaw>(lattice.spacing);
  }
  editor.set_laws(std::move(bond_law), std::move(contact_law));
  return model;
}

}  // namespace latfrac
