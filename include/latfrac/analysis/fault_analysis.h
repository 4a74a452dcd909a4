// Fault geometry of a run: broken bonds grouped into faults, each fitted by a line or plane.
//
// The broken bonds of one snapshot (pre-cuts excluded) become points at their reference
// midpoints. Points closer than link_distance_spacings * spacing are linked; each connected
// component is a cluster. A cluster is fitted by total least squares (principal component
// analysis of its points' covariance): in 2-D a line in the x-z plane along the principal
// eigenvector, in 3-D a plane whose normal is the eigenvector of the smallest variance. The
// dip is the angle of that line or plane from the horizontal; alpha = 90 - dip is its angle
// to sigma1, which gravity makes vertical (model.md section 7; Coulomb expects
// alpha = 45 - psi / 2).
//
// A cluster whose second variance is comparable to its first (2-D), or whose smallest is
// comparable to its middle one (3-D), has no well-defined line or plane: a shattered region.
// So has a cluster that fills the lattice across its fitted line or plane, such as a thin
// slab shattered throughout, which is flat only because the slab is. Such a cluster is
// reported and flagged `diffuse`, never taken for a fault. A cluster that one line or
// plane does not fit but several do, such as two faults meeting in a V, is split into its
// straight parts (k-lines or k-planes, recursively), each reported as a fault; a shattered
// region does not split into faults and stays one diffuse cluster.
//
// Each fault also gets its offset at the snapshot: the relative displacement across its
// bonds, resolved on its fitted line or plane (opening, slip, dip-slip), and its share of
// the relative motion across all the broken bonds analysed. That tells the faults that
// carry the deformation from the damage around them; `min_offset` keeps only the bonds
// whose two nodes moved apart by at least that much.
//
// Each fault then gets a role: one of the two faults of the graben (the pair bounding the
// block that subsided most), the fault through or from the tip of the pre-cut, a wall fault
// (one lying along a side wall, where the loading holds the body), or other. A run's
// headline angles are the graben's and the pre-cut fault's, not the largest cluster's,
// which is often a wall fault. docs/fault-analysis.md gives the method, the splitting
// rule, the units and sign conventions, the graben rule and the role rule.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "latfrac/fracture/run_result.h"

namespace latfrac {

struct FaultOptions {
  double link_distance_spacings = 1.5;  // points closer than this many spacings are linked
  std::int64_t min_bonds = 5;           // smaller clusters are dropped
  double diffuse_variance_ratio = 0.3;  // variance ratio above which a cluster is diffuse
  // A fault's points scatter about a spacing from its fitted line or plane; a cluster
  // whose rms distance exceeds this many spacings is a shattered region, diffuse too.
  double diffuse_rms_spacings = 3.0;
  // A fault is thin compared with the lattice's width along its normal. A cluster whose
  // thickness (sqrt(12) x its rms distance) exceeds this share of that width fills the
  // lattice across, as a shattered thin slab does: diffuse too.
  double diffuse_fill_share = 0.5;
  // A cluster that is diffuse, or whose rms distance exceeds this many spacings, is tried
  // for a split into straight faults (two faults that touch: a V, a Y, a zigzag).
  double split_rms_spacings = 1.5;
  int max_split_depth = 3;  // levels of dividing a cluster into parts; 0: never split
  // A fault with at least wall_share of its points within wall_distance_spacings of a side
  // wall (x = min or max of the lattice) lies along that wall: role "wall".
  double wall_distance_spacings = 3.0;
  double wall_share = 0.5;
  // m: only broken bonds whose nodes' relative displacement |u_j - u_i| at the snapshot is
  // at least this are analysed (the moving ones); 0: every broken bond.
  double min_offset = 0;
};

// What a fault is in the run (docs/fault-analysis.md, "Roles"). A fault that is both a
// graben fault and the pre-cut fault has the role graben; FaultReport::precut_fault still
// points to it.
enum class FaultRole { graben, precut, wall, other };
const char* to_string(FaultRole role);

struct Fault {
  std::int64_t bonds = 0;                     // broken bonds in the cluster
  double tensile_share = 0, shear_share = 0;  // fractions of its bonds by break mode
  std::array<double, 3> centroid{};           // m
  // Unit normal of the fitted line (in the x-z plane) or plane, pointing up (z >= 0).
  std::array<double, 3> normal{};
  double dip_deg = 0;    // dip from horizontal, 0..90
  double alpha_deg = 0;  // angle to the vertical (sigma1), = 90 - dip
  // +1: the fault descends towards +x, -1: towards -x, 0: vertical or horizontal within 1 deg.
  int dip_direction = 0;
  // 2-D: length along the fitted line (m); 3-D: area of the fitted plane patch (m^2).
  double extent = 0;
  double fit_rms = 0;  // rms distance of the points from the fitted line/plane, m
  // 2-D: second / first principal variance; 3-D: smallest / middle. Small for a clean fault.
  double variance_ratio = 0;
  // Thickness sqrt(12) fit_rms over the lattice's width along the normal; near 1 for a
  // cluster that fills the lattice across (a shattered thin slab).
  double fill_share = 0;
  bool diffuse = false;  // too round, too thick or filling the lattice (FaultOptions): not a fault
  // Share of its points within FaultOptions::wall_distance_spacings of a side wall.
  double wall_share = 0;
  // m: the distance from its nearest point to the nearest pre-cut bond's midpoint; +inf when
  // the run has no pre-cut.
  double precut_distance = std::numeric_limits<double>::infinity();
  FaultRole role = FaultRole::other;
  // The relative displacement across its bonds at the snapshot (m), each bond's the
  // displacement of its node on the side the normal points to (above the fault) less the
  // other's, resolved on the fitted line or plane and averaged over the bonds:
  // opening along the normal (positive: the faces apart), slip its magnitude along the
  // fault, dip-slip its component down the dip (positive: the upper side went down the
  // dip, a normal fault's sense; NaN when dip_direction is 0).
  double opening = 0, slip = 0, dip_slip = 0;
  // Its share of the relative motion, the sum of |u_j - u_i| over the bonds analysed
  // (FaultReport::relative_motion); 0 when nothing moved.
  double motion_share = 0;
};

struct Graben {
  std::size_t left_fault = 0, right_fault = 0;     // indices into FaultReport::faults
  double left_surface_x = 0, right_surface_x = 0;  // m: where the fitted traces meet the surface
  double apex_depth = 0;  // m below the surface where the two traces, extended, meet
  // m: mean vertical displacement of the surface outside the faults minus that of the surface
  // between them (positive: the block went down). NaN when either side has no surface node.
  double surface_subsidence = 0;
};

struct FaultReport {
  int dim = 2;
  double lambda = 0;              // the snapshot analysed
  std::int64_t broken_bonds = 0;  // pre-cuts excluded
  double min_offset = 0;          // m: FaultOptions::min_offset
  std::int64_t moved_bonds = 0;   // of the broken bonds, those analysed (moved by min_offset)
  double relative_motion = 0;     // m: the sum of |u_j - u_i| over the bonds analysed
  std::vector<Fault> faults;      // largest first
  std::vector<Graben> grabens;    // ordered by left_surface_x
  std::int64_t precut_bonds = 0;  // bonds a pre-cut broke (break events of mode 2)
  // Index into grabens of the graben: the one whose block subsided most; empty when none.
  std::optional<std::size_t> graben;
  // Index into faults of the fault through or from the tip of the pre-cut; empty when none.
  std::optional<std::size_t> precut_fault;
};

inline constexpr std::size_t kLastSnapshot = std::numeric_limits<std::size_t>::max();

// Analyses snapshot `index` (default: the last). Throws InputError when the result has no
// snapshots, the index is out of range, the arrays disagree in size, or an option is out of
// range.
FaultReport analyze_faults(const RunResult& result, std::size_t index = kLastSnapshot,
                           const FaultOptions& options = {});

// The share of the broken bonds analysed (pre-cuts excluded; all of them unless
// min_offset) outside the two faults of the graben (FaultReport::graben): the faults
// issue's measure of how much damage lies off the faults. 1 when there is no graben, 0
// when nothing broke.
double share_outside_graben(const FaultReport& report);
// The share of the relative motion on the graben's two faults; 0 when there is no graben
// or nothing moved.
double graben_motion_share(const FaultReport& report);

// A readable table for `latfrac analyze`.
std::string to_text(const FaultReport& report);
// One JSON object; non-finite numbers are written as null.
std::string to_json(const FaultReport& report);

}  // namespace latfrac
