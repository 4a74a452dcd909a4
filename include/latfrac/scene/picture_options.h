// What a picture of a run shows: the [output] picture keys and `latfrac render`'s options.
//
// The render layer draws these (include/latfrac/render/render.h); they live with the scene
// because a problem file names them, and the problem-file reader, below the render layer,
// checks them. docs/result-files.md shows one picture of each kind with its command.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace latfrac {

// section: a vertical cut (a 2-D run, or a slab of a 3-D block at a chosen y or x);
// map: the top surface of a 3-D block seen from above; oblique: a 3-D block seen
// obliquely from above, its broken bonds (or fault planes) with a depth cue.
enum class PictureView { section, map, oblique };

// cracks: every broken bond a segment in the colour of its mode (tensile, shear, pre-cut)
// over the deformed lattice; particles: the paper's style, a node red when it touches a
// broken bond.
enum class CrackStyle { cracks, particles };

// A value on each node, drawn in a colour map with a colour bar.
enum class NodeField {
  none,
  displacement,   // |u|, m
  ux, uy, uz,     // m
  sigma_xx, sigma_yy, sigma_zz, sigma_xz,  // Pa, tension positive
  sigma_mean,     // (xx + yy + zz) / 3, Pa
  von_mises,      // sqrt(3 J2), Pa
  sqrt_j2,        // sqrt(J2), Pa
  failure_index,  // f of the node's most loaded intact bond
};

enum class SectionAxis { y, x };  // the section is the plane of constant y (or x)

// The largest displacement magnification a picture takes (output.exaggeration and
// render --exaggeration): far beyond any use, and small enough that an exaggerated motion
// stays a finite number.
inline constexpr double max_exaggeration = 1e12;

struct PictureOptions {
  PictureView view = PictureView::section;
  CrackStyle style = CrackStyle::cracks;
  NodeField field = NodeField::none;
  bool faults = false;  // draw the fault analysis: fitted faults, alpha and dip, grabens
  // 3-D sections: the reference coordinate of the cut, m (default: the middle of y).
  SectionAxis section_axis = SectionAxis::y;
  std::optional<double> section_at{};
  int width = 1600;          // pixels (points for SVG and PDF)
  double exaggeration = -1;  // displacement magnification; < 0: the scene's
  // m: draw only the broken bonds whose nodes moved apart by at least this (|u_j - u_i|
  // at the snapshot; render --min-offset), and analyse only those for the faults; 0: all.
  double min_offset = 0;
};

// The names used on the command line and in problem files, in enumeration order.
const std::vector<std::string_view>& picture_view_names();
const std::vector<std::string_view>& crack_style_names();
const std::vector<std::string_view>& node_field_names();  // "none" first
// The picture file formats, by extension.
const std::vector<std::string_view>& picture_format_names();

std::string_view name_of(PictureView view);
std::string_view name_of(CrackStyle style);
std::string_view name_of(NodeField field);

// The enumerator named `name`, or nothing when no name matches.
std::optional<PictureView> picture_view_named(std::string_view name);
std::optional<CrackStyle> crack_style_named(std::string_view name);
std::optional<NodeField> node_field_named(std::string_view name);

// "a, b or c", for messages.
std::string list_of_names(const std::vector<std::string_view>& names);

}  // namespace latfrac
