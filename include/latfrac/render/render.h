// Pictures of a run: a snapshot drawn with Cairo as PNG, SVG or PDF (by the file's extension).
//
// What a picture shows is chosen by PictureOptions (scene/picture_options.h): a section
// (a 2-D run, or a slab of a 3-D block at a chosen y or x), a map of a 3-D block's top
// surface, or an oblique 3-D view; the broken bonds as segments coloured by break mode or
// the paper's red particles; a node field in a colour map with a colour bar; the fault
// analysis on top. Positions are deformed, X + exaggeration * u. Axes and the scale bar are
// in km; the title names the scene, the criterion, lambda and the exaggeration.
// docs/result-files.md shows one picture of each kind with its command.
#pragma once

#include <array>
#include <cstddef>
#include <string>

#include "latfrac/fracture/run_result.h"
#include "latfrac/scene/picture_options.h"

namespace latfrac {

enum class PictureFormat { png, svg, pdf };

// The format named by the path's extension (.png, .svg, .pdf, any case); InputError for any
// other extension.
PictureFormat picture_format_of(const std::string& path);

// What a picture holds, for the caller and for tests: where the plot lies in the picture
// and how a point lands there, the field's range and the colour bar's end labels.
struct PictureReport {
  int width = 0, height = 0;                // pixels (points for SVG and PDF)
  std::array<double, 4> frame{};            // the plot area: left, top, right, bottom, pixels
  std::array<double, 4> window{};           // what it shows: h_min, h_max, v_min, v_max, m
  std::array<double, 3> right{}, up{};      // the picture's h and v directions in x y z
  double field_min = 0, field_max = 0;      // SI units, over the nodes drawn
  std::string colour_bar_low, colour_bar_high;  // the colour bar's end labels ("" without)
  std::size_t nodes_drawn = 0, broken_bonds_drawn = 0;
  // Empty, or a sentence for the user: the exaggeration moves the nodes by more than ten
  // times the lattice's size, so the lattice is drawn as a speck in the window that holds
  // the deformed positions; it names an exaggeration that fits.
  std::string note;

  // Where a deformed position (m) lands in the picture, pixels from the top-left corner.
  std::array<double, 2> pixel_of(const std::array<double, 3>& position) const;
};

// Index of the snapshot whose lambda is nearest to `lambda` (the last one when lambda is
// NaN). Throws InputError when there are no snapshots.
std::size_t snapshot_nearest(const RunResult& result, double lambda);

// Draws snapshot `index` into `path`. Throws InputError, before any file is made, when the
// result is inconsistent or an option does not fit it (an unknown format, a 2-D result
// asked for a map, a section outside the block); latfrac::Error when a Cairo call or the
// write fails. The file is written under a temporary name and renamed when complete.
PictureReport render_picture(const RunResult& result, std::size_t index, const std::string& path,
                             const PictureOptions& options = {});

}  // namespace latfrac
