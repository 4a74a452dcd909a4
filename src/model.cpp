// Builds the mechanical model of a scene and evaluates its forces.
#include "latfrac/model.h"

#include <limits>
#include <optional>
#include <random>

#include "latfrac/calibration.h"
#include "latfrac/criterion.h"
#include "latfrac/error.h"
#include "latfrac/precut.h"

namespace latfrac {
namespace {

// Which condition wins where two faces meet on one component: the most restrictive.
int rank_of(FaceCondition condition) {
  switch (condition) {
    case FaceCondition::free:
      return 0;
    case FaceCondition::roller:
      return 1;
    case FaceCondition::extension:
      return 2;
    case FaceCondition::fixed:
      return 3;
  }
  return 0;
}

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

// Moduli and strengths per bond: the layer holding the bond's midpoint, times a random
// factor uniform in [1 - spread, 1 + spread] when the scene names heterogeneity.
void assign_strengths(const Scene& scene, Model& model) {
  const Lattice& lattice = model.lattice;
  const std::int64_t bonds = lattice.bond_count();
  model.bond_young.resize(bonds);
  model.bond_shear_modulus.resize(bonds);
  model.bond_sigma0.assign(bonds, 0.0);
  model.bond_tau0.assign(bonds, 0.0);
  std::optional<CriterionParameters> criterion;
  if (scene.strength) criterion = resolve_criterion(*scene.strength, lattice.dim);
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
    const double sigma0 = layer && layer->sigma0 ? *layer->sigma0 : criterion->sigma0;
    double tau0 = layer && layer->tau0 ? *layer->tau0 : criterion->tau0;
    // A layer that sets its own sigma0 but not tau0 scales a derived tau0 with it.
    if (layer && layer->sigma0 && !layer->tau0 && !scene.strength->tau0)
      tau0 *= sigma0 / criterion->sigma0;
    model.bond_sigma0[b] = scale * sigma0;
    model.bond_tau0[b] = scale * tau0;
  }
}

}  // namespace

DofMap build_dof_map(const Lattice& lattice, const std::array<FaceCondition, face_count>& faces) {
  const std::vector<int> axes = lattice.axes();
  const int dim = lattice.dim;
  DofMap map;
  map.dim = dim;
  const std::int64_t dof_count = lattice.node_count() * dim;
  map.prescribed_base.assign(dof_count, 0.0);
  map.prescribed_rate.assign(dof_count, 0.0);
  std::vector<int> rank(dof_count, 0);
  const Vec3 centre = lattice.extent / 2;
  for (std::int64_t node = 0; node < lattice.node_count(); ++node) {
    for (int f = 0; f < face_count; ++f) {
      const Face face = static_cast<Face>(f);
      const int face_axis = f / 2;
      if (dim == 2 && face_axis == 1) continue;
      if (!lattice.on_face(node, face)) continue;
      const FaceCondition condition = faces[f];
      for (int c = 0; c < dim; ++c) {
        const bool normal = axes[c] == face_axis;
        const bool constrains =
            condition == FaceCondition::fixed || (normal && condition != FaceCondition::free);
        const std::int64_t dof = node * dim + c;
        if (!constrains || rank_of(condition) <= rank[dof]) continue;
        rank[dof] = rank_of(condition);
        map.prescribed_rate[dof] = condition == FaceCondition::extension
                                       ? lattice.positions[node][face_axis] - centre[face_axis]
                                       : 0.0;
      }
    }
  }
  map.free_index.assign(dof_count, -1);
  for (std::int64_t dof = 0; dof < dof_count; ++dof) {
    if (rank[dof] == 0) map.free_index[dof] = map.free_count++;
  }
  return map;
}

Model build_model(const Scene& scene) {
  validate_material(scene.material);
  for (const Layer& layer : scene.layers) validate_material(layer.material, "layer");
  Model model;
  model.lattice = build_lattice(scene.lattice);
  const Lattice& lattice = model.lattice;
  const int dim = lattice.dim;

  const std::int64_t bonds = lattice.bond_count();
  model.normal_stiffness.resize(bonds);
  model.shear_stiffness.resize(bonds);
  model.intact.assign(bonds, 1);
  for (std::int64_t b = 0; b < bonds; ++b) {
    const Bond& bond = lattice.bonds[b];
    const double mid_z = 0.5 * (lattice.positions[bond.i].z() + lattice.positions[bond.j].z());
    const SpringConstants k = spring_constants(dim, material_at(scene, mid_z), lattice.spacing);
    const double scale = bond.kind == BondKind::next_nearest ? next_nearest_fraction : 1.0;
    model.normal_stiffness[b] = scale * k.normal;
    model.shear_stiffness[b] = scale * k.shear;
  }

  assign_strengths(scene, model);
  model.precut.assign(bonds, 0);
  for (std::int64_t b : bonds_crossing_precuts(lattice, scene.precuts)) {
    model.precut[b] = 1;
    model.intact[b] = 0;
  }
  model.contact = scene.contact.has_value();
  model.contact_active.assign(bonds, 0);

  model.dofs = build_dof_map(lattice, scene.faces);
  model.external_force = Vector::Zero(model.dofs.dof_count());
  model.node_poisson.resize(lattice.node_count());
  for (std::int64_t n = 0; n < lattice.node_count(); ++n) {
    const Material& material = material_at(scene, lattice.positions[n].z());
    model.node_poisson[n] = material.poisson;
    if (scene.gravity) {
      const int z_component = dim - 1;
      model.external_force[n * dim + z_component] =
          -material.density * scene.gravity->g * lattice.node_volume;
    }
  }
  if (scene.large_kinematics) {
    model.law = std::make_unique<LargeKinematics>();
  } else {
    model.law = std::make_unique<SmallKinematics>();
  }
  return model;
}

double max_abs(const Vector& v) {
  if (!v.allFinite()) return std::numeric_limits<double>::infinity();
  return v.size() ? v.cwiseAbs().maxCoeff() : 0.0;
}

Vector Model::full_displacement(const Vector& free_displacement, double lambda) const {
  Vector u(dofs.dof_count());
  for (std::int64_t dof = 0; dof < dofs.dof_count(); ++dof) {
    const std::int64_t f = dofs.free_index[dof];
    u[dof] = f >= 0 ? free_displacement[f]
                    : dofs.prescribed_base[dof] + lambda * dofs.prescribed_rate[dof];
  }
  return u;
}

Vec3 Model::node_displacement(const Vector& displacement, std::int64_t node) const {
  if (lattice.dim == 2) return {displacement[2 * node], 0.0, displacement[2 * node + 1]};
  return {displacement[3 * node], displacement[3 * node + 1], displacement[3 * node + 2]};
}

// Adds bond b's force to both its nodes: +t on j, -t on i (t its tension vector).
void Model::add_bond_force(const Vector& displacement, std::int64_t b, Vector& force) const {
  const bool in_contact = contact_capable(b) && contact_active[b];
  if (!intact[b] && !in_contact) return;
  const Bond& bond = lattice.bonds[b];
  const Vec3& n0 = lattice.bond_direction[b];
  const Vec3 du = bond_displacement(displacement, b);
  const Vec3 t = intact[b] ? law->tension({n0, lattice.bond_length[b]}, du, normal_stiffness[b],
                                          shear_stiffness[b])
                           : Vec3(normal_stiffness[b] * n0.dot(du) * n0);
  const int d = dim();
  for (int c = 0; c < d; ++c) {
    const double component = t[d == 2 ? 2 * c : c];
    force[bond.j * d + c] += component;
    force[bond.i * d + c] -= component;
  }
}

Vector Model::internal_force(const Vector& displacement) const {
  Vector force = Vector::Zero(dofs.dof_count());
  for (std::int64_t b = 0; b < lattice.bond_count(); ++b) add_bond_force(displacement, b, force);
  return force;
}

Vector Model::internal_force(const Vector& displacement,
                             const std::vector<std::int64_t>& bonds) const {
  Vector force = Vector::Zero(dofs.dof_count());
  for (std::int64_t b : bonds) add_bond_force(displacement, b, force);
  return force;
}

Vector Model::residual(const Vector& free_displacement, double lambda) const {
  const Vector unbalanced =
      internal_force(full_displacement(free_displacement, lambda)) - external_force;
  Vector r(dofs.free_count);
  for (std::int64_t dof = 0; dof < dofs.dof_count(); ++dof) {
    if (dofs.free_index[dof] >= 0) r[dofs.free_index[dof]] = unbalanced[dof];
  }
  return r;
}

Vector Model::reactions(const Vector& displacement) const {
  Vector r = internal_force(displacement) - external_force;
  for (std::int64_t dof = 0; dof < dofs.dof_count(); ++dof) {
    if (dofs.free_index[dof] >= 0) r[dof] = 0;
  }
  return r;
}

}  // namespace latfrac
