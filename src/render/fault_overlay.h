// The fault analysis drawn over a picture: fitted faults with alpha and dip, graben blocks.
//
// A fault's fitted line or plane is placed at reference positions, moved by the
// exaggerated mean displacement of the nodes within two spacings of its centroid, so that
// it sits on the deformed lattice. Diffuse clusters are not faults and are not drawn.
// - sections and maps: each fault's trace in the view plane, dashed, labelled with alpha and
//   dip at its upper end; in a section whose h axis is x, each graben is the shaded triangle
//   between its two traces, from the surface down to where they meet;
// - oblique: each fault plane as a translucent polygon, the plane cut by the block and
//   limited to the fault's depth range, labelled at its top.
#pragma once

#include <vector>

#include "canvas.h"
#include "latfrac/analysis/fault_analysis.h"
#include "picture_layers.h"
#include "scene_view.h"

namespace latfrac {

// Draws one layer of the report's faults and grabens: areas (graben triangles, the oblique
// view's planes) go under the cracks, lines (traces) over them, labels last. Returns the
// legend entries for what is drawn.
enum class FaultLayer { areas, lines, labels };
std::vector<LegendEntry> draw_faults(Canvas& canvas, const SceneView& view,
                                     const PictureLayout& layout, const RunResult& result,
                                     const Snapshot& snapshot, const FaultReport& report,
                                     FaultLayer layer);

}  // namespace latfrac
