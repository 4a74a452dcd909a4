// What a scene asks of the layers below it.
#include "latfrac/scene/scene.h"

namespace latfrac {

Schedule schedule_of(const Scene& scene) {
  return {scene.loading.total, scene.stepping, scene.output.snapshots};
}

}  // namespace latfrac
