// Pictures of a run: a snapshot drawn as an x-z cross-section PNG in the paper's style.
//
// Nodes are dots at their deformed position X + exaggeration * u (x to the right, z up),
// dark grey, or red when they touch a broken bond (pre-cut bonds included) - "particles
// next to broken bonds are red". A 3-D result is drawn as one lattice layer of nodes
// near the middle of y. Axes are in km; the title names the scene, the criterion, lambda
// and the exaggeration. Red (R > 180, G < 80, B < 80) is used for nothing else.
#pragma once

#include <cstddef>
#include <string>

#include "latfrac/fracture/run_result.h"

namespace latfrac {

struct RenderOptions {
  int width = 1600;          // pixels; the height follows from the section's aspect ratio
  double exaggeration = -1;  // < 0: use result.scene.exaggeration
};

// Index of the snapshot whose lambda is nearest to `lambda` (the last one when lambda is
// NaN). Throws InputError when there are no snapshots.
std::size_t snapshot_nearest(const RunResult& result, double lambda);

// Draws snapshot `index` as a cross-section PNG. Throws InputError when the result is
// inconsistent or the options are out of range, latfrac::Error on I/O failure; a failed
// write leaves no file at `png_path`.
void render_png(const RunResult& result, std::size_t index, const std::string& png_path,
                const RenderOptions& options = {});

}  // namespace latfrac
