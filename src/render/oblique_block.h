// The block of an oblique view: its twelve edges, hidden ones dashed, and km ticks on three.
#pragma once

#include "canvas.h"
#include "picture_layers.h"
#include "scene_view.h"

namespace latfrac {

// The deformed block's bounding box: the edges that meet at its farthest corner are hidden
// (dashed, light); x is ticked along the near bottom edge, y along the bottom edge at the
// near end of x, z up the near vertical edge.
void draw_block(Canvas& canvas, const SceneView& view, const PictureLayout& layout);

}  // namespace latfrac
