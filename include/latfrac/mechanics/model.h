// The mechanical model of a scene: lattice, springs, pair states, supports, loads and laws.
//
// The lattice, the springs, the strengths and the loads are fixed once built. What a run
// changes, the state of each pair (intact, open or closed, pair_state.h) and the supports
// (which degrees of freedom are prescribed, supports.h), can be read by everyone but
// changed only through a ModelEditor: the equilibrium solver owns the one a run uses, so
// its factor follows every change (solvers/equilibrium.h). scene/model_builder.h builds a
// Model from a problem file's scene.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "latfrac/base/linear_algebra.h"
#include "latfrac/geometry/lattice.h"
#include "latfrac/mechanics/bond_law.h"
#include "latfrac/mechanics/contact_law.h"
#include "latfrac/mechanics/friction_law.h"
#include "latfrac/mechanics/pair_state.h"
#include "latfrac/mechanics/supports.h"

namespace latfrac {

class Model {
 public:
  Lattice lattice;
  std::vector<double> normal_stiffness;  // kn per bond
  std::vector<double> shear_stiffness;   // ks per bond
  std::vector<std::uint8_t> precut;      // per bond: crosses a pre-cut (starts broken)
  // Per-bond moduli and strengths (layers and heterogeneity make them differ), Pa.
  std::vector<double> bond_young, bond_shear_modulus, bond_sigma0, bond_tau0;
  std::vector<double> node_poisson;  // per node, for the 2-D out-of-plane stress
  Vector external_force;             // per dof (gravity), N (2-D: N per metre)
  // An initial stress (docs/model.md, "Initial stress"): per bond, the relative
  // displacement d_b (m) its springs already have at zero displacement, so that it carries
  // its facet's traction t0 = sigma0 n0 A (normal part -kn d_b.n0, shear part -ks times
  // d_b's transverse part); per node, the initial vertical stress sigma0_v it reads (Pa)
  // and, for all nodes, K = sigma0_h / sigma0_v (the 2-D out-of-plane stress keeps
  // K sigma0_v). Both vectors empty: the lattice starts unstressed.
  std::vector<Vec3> prestretch;
  std::vector<double> node_initial_stress;
  double initial_stress_ratio = 1;
  // A pressure on the top face (Pa; gravity.overburden): each top face piece of a random
  // lattice carries -p A e_z at its centroid, in external_force and in the node stresses.
  double top_pressure = 0;
  // Which way a broken bond's contact acts (docs/model.md, section 8): empty, along the
  // bond (the paper's model); otherwise per bond the unit normal of its crack's plane
  // (contact.normal = "crack", criteria/crack_plane.h), oriented from i to j: a pre-cut's
  // normal from the start, a bond broken in the run the one its failure picked (set by
  // ModelEditor::set_contact_normal while it is still intact), else the bond's direction.
  std::vector<Vec3> contact_normal;
  double crack_friction_angle = 0;  // phi of the crack's Coulomb plane, radians

  int dim() const { return lattice.dim; }
  const DofMap& dofs() const { return dofs_; }

  // Pair states.
  PairState state(std::int64_t bond) const { return states_[bond]; }
  bool intact(std::int64_t bond) const { return states_[bond] == PairState::intact; }
  const std::vector<PairState>& pair_states() const { return states_; }
  // Per bond, 1 while intact: the result files' bond_intact.
  std::vector<std::uint8_t> intact_flags() const;
  // Contact (when the scene names it): a broken nearest-neighbour, Delaunay (random
  // lattice) or pre-cut bond keeps a compression-only normal spring kn, frictionless
  // (contact_law.h) or with Coulomb friction (friction_law.h).
  bool has_contact() const { return contact_law_ != nullptr; }
  // With friction: its contacts remember (ContactMemory per bond, kept here).
  bool has_friction() const { return contact_law_ && contact_law_->remembers(); }
  const std::vector<ContactMemory>& contact_memory() const { return memory_; }
  const InteractionLaw* contact_law() const { return contact_law_.get(); }
  // Can bond b's faces touch once it is broken (a nearest-neighbour, Delaunay or pre-cut
  // bond, in a scene with contact)?
  bool can_touch(std::int64_t bond) const {
    return has_contact() && (lattice.bonds[bond].kind != BondKind::next_nearest || precut[bond]);
  }
  // Is bond b broken and able to touch (so its contact law acts)?
  bool contact_capable(std::int64_t bond) const { return !intact(bond) && can_touch(bond); }

  // Laws.
  const BondLaw& bond_law() const { return *bond_law_; }
  // The law acting on bond b in its state: the bond law while intact, the contact law of a
  // contact-capable broken bond, and none for a broken bond that cannot touch.
  const InteractionLaw* law_of(std::int64_t bond) const {
    if (intact(bond)) return bond_law_.get();
    return contact_capable(bond) ? contact_law_.get() : nullptr;
  }
  // Bond b's reference geometry and springs (and its memory, with friction), in its
  // state: an intact bond along its direction, a broken one along its contact's.
  PairSprings springs(std::int64_t bond) const {
    return intact(bond) ? springs_along(bond, lattice.bond_direction[bond]) : contact_springs(bond);
  }
  // The springs of bond b's contact, whatever its state (for entering it).
  PairSprings contact_springs(std::int64_t bond) const {
    return springs_along(bond, contact_direction(bond));
  }
  // The unit normal bond b's contact acts along (n . du, its opening).
  const Vec3& contact_direction(std::int64_t bond) const {
    return contact_normal.empty() ? lattice.bond_direction[bond] : contact_normal[bond];
  }
  // Whether a bond's contact acts across its crack's plane (contact.normal = "crack").
  bool contacts_along_cracks() const { return !contact_normal.empty(); }
  bool has_prestress() const { return !prestretch.empty(); }
  // True when every law is linear (paths between events are affine).
  bool is_linear() const { return bond_law_->is_linear(); }

  // The full displacement (every dof) from the free part at extension strain lambda.
  Vector full_displacement(const Vector& free_displacement, double lambda) const;
  // The free part of a full vector (every dof).
  Vector free_part(const Vector& full) const;
  // Internal (spring) force per dof: the gradient of the stored energy.
  Vector internal_force(const Vector& displacement) const;
  // The same, summed over the listed bonds only.
  Vector internal_force(const Vector& displacement, const std::vector<std::int64_t>& bonds) const;
  // Out-of-balance force on the free dofs: internal minus external. Zero at equilibrium.
  Vector residual(const Vector& free_displacement, double lambda) const;
  // Reaction forces on the prescribed dofs (internal minus external), zero on free dofs.
  Vector reactions(const Vector& displacement) const;
  // The displacement of node n as a 3-vector (y = 0 in 2-D).
  Vec3 node_displacement(const Vector& displacement, std::int64_t node) const {
    if (lattice.dim == 2) return {displacement[2 * node], 0.0, displacement[2 * node + 1]};
    return {displacement[3 * node], displacement[3 * node + 1], displacement[3 * node + 2]};
  }
  // The relative displacement that bond b's law reads: u_j - u_i, less its prestretch
  // d_b when the scene starts stressed (what the pair's springs are stretched by, measured
  // from their unstressed state).
  Vec3 bond_displacement(const Vector& displacement, std::int64_t bond) const {
    Vec3 du = relative_motion(displacement, bond);
    if (!prestretch.empty()) du -= prestretch[bond];
    return du;
  }
  // u_j - u_i alone: for a rate or a direction (an affine path's slope, a Newton step).
  Vec3 relative_motion(const Vector& displacement, std::int64_t bond) const {
    return node_displacement(displacement, lattice.bonds[bond].j) -
           node_displacement(displacement, lattice.bonds[bond].i);
  }
  // Bond b's tension (its law's, in its state) at the full displacement; zero without a law.
  Vec3 bond_tension(const Vector& displacement, std::int64_t bond) const;
  // The lattice's node-to-bond index, built on the first call and again when the
  // lattice's bonds or nodes have changed in number. Call it outside threaded blocks.
  const NodeBonds& node_bonds() const;
  // Whether bond b exerts a force: not an open pair, and with a law.
  bool carries_force(std::int64_t b) const;
  // Adds bond b's force to `force`: +t on node j, -t on node i.
  void add_bond_force(const Vector& displacement, std::int64_t bond, Vector& force) const;

 private:
  friend class ModelEditor;
  std::vector<PairState> states_;
  DofMap dofs_;
  std::unique_ptr<BondLaw> bond_law_;
  std::unique_ptr<InteractionLaw> contact_law_;  // null without contact
  std::vector<ContactMemory> memory_;            // per bond with friction, else empty
  mutable NodeBonds node_bonds_;                 // a cache of node_bonds(lattice)
  PairSprings springs_along(std::int64_t bond, const Vec3& direction) const {
    return {direction, lattice.bond_length[bond], normal_stiffness[bond], shear_stiffness[bond],
            memory_.empty() ? nullptr : &memory_[bond]};
  }
};

// The one way to change what a model's run changes (its pair states and supports) and
// to set its laws. Builders use it before any solver exists; during a run only the
// equilibrium solver does, so that its factor follows every change. Tests use it to set
// up states directly.
class ModelEditor {
 public:
  explicit ModelEditor(Model& model) : model_(model) {}
  // contact_law: a ContactLaw, a FrictionalContactLaw, or null (no contact).
  void set_laws(std::unique_ptr<BondLaw> bond_law, std::unique_ptr<InteractionLaw> contact_law);
  void set_memory(std::int64_t bond, const ContactMemory& memory) { model_.memory_[bond] = memory; }
  // The normal bond b's contact will act along (contacts along cracks only): set while the
  // bond is intact, so that no factor holds the old one.
  void set_contact_normal(std::int64_t bond, const Vec3& normal);
  // Every bond intact.
  void reset_states();
  void set_state(std::int64_t bond, PairState state) { model_.states_[bond] = state; }
  void set_dofs(DofMap dofs) { model_.dofs_ = std::move(dofs); }
  // Holds the listed nodes along the listed components (0 .. dim-1) at the given full
  // displacement: those free dofs become prescribed (base = their value, rate 0), and the
  // free dofs are numbered again in order.
  void hold(const std::vector<std::int64_t>& nodes, const std::vector<int>& components,
            const Vector& displacement);

 private:
  Model& model_;
};

}  // namespace latfrac
