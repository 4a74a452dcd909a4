// What a picture draws of a snapshot: its nodes and broken bonds on the picture plane.
//
// A view projects deformed positions (X + exaggeration * u) orthographically onto the
// picture plane: h along `right`, v along `up`, and a depth along `away` (from the viewer).
// - section: a 2-D run whole; of a 3-D block the slab of nodes within half a spacing of
//   the node layer nearest the chosen y (or x), with the broken bonds whose midpoints lie
//   in that slab;
// - map: the top layer of a 3-D block (nodes within half a spacing of the highest), seen
//   from above, with the broken bonds whose midpoints lie in that layer's slab;
// - oblique: a 3-D block from the front, 20 degrees round from the x axis and 25 degrees
//   above the horizon; its top layer's nodes and every broken bond.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "latfrac/fracture/run_result.h"
#include "latfrac/scene/picture_options.h"

namespace latfrac {

using Vec3 = std::array<double, 3>;

inline double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

struct ViewPoint {
  double h = 0, v = 0;
};

struct ViewNode {
  std::size_t node = 0;
  ViewPoint at;
};

struct ViewBond {
  std::size_t bond = 0;
  ViewPoint from, to;
  double depth = 0;       // of the midpoint, m along `away`
  std::int8_t mode = -1;  // the break mode of its last break event; -1 when it has none
};

struct SceneView {
  PictureView kind = PictureView::section;
  Vec3 right{1, 0, 0}, up{0, 0, 1}, away{0, 1, 0};
  std::vector<ViewNode> nodes;
  std::vector<ViewBond> broken;           // back to front (oblique) or in bond order
  std::vector<bool> touches_broken;       // per node of the lattice
  double plane = 0;  // sections and maps: where the view plane lies along `away`, m
  double h_min = 0, h_max = 1, v_min = 0, v_max = 1;  // m, padded
  double spacing = 1;                     // m
  double exaggeration = 1;
  double min_offset = 0;                  // m: broken bonds that moved less are not drawn
  std::string h_title, v_title;           // axis titles ("" for none)
  std::string where;                      // for the title: "section y = 4.5 km", ""
  Vec3 box_low{}, box_high{};             // the deformed lattice's bounding box, m

  ViewPoint project(const Vec3& p) const { return {dot(p, right), dot(p, up)}; }
  double depth(const Vec3& p) const { return dot(p, away); }
};

// The deformed position of `node`.
Vec3 deformed_position(const RunResult& result, const Snapshot& snapshot, std::size_t node,
                       double exaggeration);

// The node spacing in m: the scene's, or else the shortest bond's reference length.
double node_spacing(const RunResult& result);

// The view `options` ask for. Throws InputError when it does not fit the result (a map or
// oblique view of a 2-D run, a section outside the block).
SceneView make_view(const RunResult& result, const Snapshot& snapshot,
                    const PictureOptions& options, double exaggeration);

}  // namespace latfrac
