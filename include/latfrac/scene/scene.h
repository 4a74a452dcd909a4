// The scene: everything a problem file says, resolved and validated, in SI units.
//
// A Scene gathers the parameters each layer defines (the lattice spec, the material, the
// supports, the strength, the solver options, the schedule) with those only a whole
// scene has (gravity, layers, heterogeneity, contact, output).
//
// A scene names its effects: an absent optional section means the effect is off
// (no [gravity], no gravity; no [strength], purely elastic; no [contact], no contact
// springs). The problem-file reader (problem_file.h) is the only producer of a Scene;
// docs/problem-files.md documents every key, its unit, default and allowed range.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "latfrac/criteria/strength.h"
#include "latfrac/fracture/schedule.h"
#include "latfrac/geometry/lattice.h"
#include "latfrac/geometry/precut.h"
#include "latfrac/mechanics/material.h"
#include "latfrac/mechanics/supports.h"
#include "latfrac/scene/picture_options.h"
#include "latfrac/solvers/solver_options.h"

namespace latfrac {

struct Gravity {
  double g = 9.81;  // m/s^2
  // How the body starts (docs/model.md, "Initial stress"): false, unstressed, so that
  // gravity loads it elastically (sigma_xx = nu / (1 - nu) sigma_zz); true, in the
  // lithostatic state sigma0 = -g (integral of rho from z to the top) I, its bonds
  // pre-stressed so that it stands under its weight without moving (random lattices).
  bool lithostatic = false;
  // With `lithostatic`: K, the initial horizontal stress over the vertical (1: isotropic;
  // below 1 an Andersonian state with sigma1 vertical, docs/model.md, "Initial stress").
  double stress_ratio = 1;
  // With `lithostatic`: p0 (Pa), the weight of rock above the lattice's top, as a pressure
  // on the top face and in the initial stress: sigma0_v = -(p0 + the lattice's own weight
  // above). A confined specimen, or a section of deeper crust (docs/model.md).
  double overburden = 0;
};

struct Loading {
  double total = 0;  // final extension strain lambda (negative: compression)
  // x_d (m): the base left of x_d moves with the left wall, right of it with the right
  // wall (a basal velocity discontinuity, docs/model.md); unset: the base is as its face
  // condition says.
  std::optional<double> basal_discontinuity;
};

struct Contact {
  bool enabled = true;
  double friction = 0;  // Coulomb's mu on closed contacts (0: frictionless), dimensionless
  // 3-D: the facets of the polygon inscribed in Coulomb's circle (friction_law.h).
  int friction_facets = 8;
  // Which way a broken bond's contact acts: along the bond (the paper's model) or across
  // the plane of the crack it stands for (docs/model.md, section 8).
  enum class Normal { bond, crack };
  Normal normal = Normal::bond;
};

// A horizontal layer z_min <= z < z_max with its own material and strength; a bond
// belongs to the layer that holds its midpoint. Unset values inherit the scene's.
struct Layer {
  double z_min = 0, z_max = 0;  // m
  Material material;
  std::optional<double> sigma0, tau0;  // Pa
};

// Random bond strength: sigma0 and tau0 of each bond are multiplied by a factor drawn
// uniformly from [1 - spread, 1 + spread] by a generator seeded with `seed`.
struct Heterogeneity {
  double spread = 0;
  std::uint64_t seed = 0;
};

struct Output {
  std::vector<double> snapshots;       // lambda values at which to store a snapshot
  double exaggeration = 1;             // displacement magnification in pictures
  bool picture = true;                 // write a picture of the final state
  std::string picture_format = "png";  // its file's extension: png, svg or pdf
  PictureOptions picture_options;      // what it shows
};

struct Scene {
  std::string name;
  std::string description;
  LatticeSpec lattice;
  Material material;
  std::array<FaceCondition, face_count> faces{
      FaceCondition::extension, FaceCondition::extension,  // x_min, x_max
      FaceCondition::roller,    FaceCondition::roller,     // y_min, y_max
      FaceCondition::roller,    FaceCondition::free};      // z_min, z_max
  std::optional<Strength> strength;
  std::optional<Gravity> gravity;
  Loading loading;
  Stepping stepping;
  std::vector<Precut> precuts;
  std::optional<Contact> contact;
  std::vector<Layer> layers;
  std::optional<Heterogeneity> heterogeneity;
  bool large_kinematics = false;
  Output output;
  SolverOptions solver;

  std::string source_path;  // the problem file, for messages and provenance
  std::string source_text;  // its full text
};

// The loading schedule a fracture run follows.
Schedule schedule_of(const Scene& scene);

// Which of the two models a scene runs (docs/model.md, "Two models"): the options it uses
// beyond the paper's model, in a fixed order ("random lattice", "internal friction",
// "contact friction", "basal discontinuity", "layers", "heterogeneity"); none for the
// paper's model.
std::vector<std::string> complete_model_options(const Scene& scene);
// "the paper's model"; "the complete model: " and its options when it has the first four
// (and any more); otherwise "the paper's model with: " and those it has.
std::string model_label(const Scene& scene);

}  // namespace latfrac
