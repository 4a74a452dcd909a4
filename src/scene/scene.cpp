// What a scene asks of the layers below it.
#include "latfrac/scene/scene.h"

#include <algorithm>
#include <array>

namespace latfrac {

Schedule schedule_of(const Scene& scene) {
  return {scene.loading.total, scene.stepping, scene.output.snapshots};
}

std::vector<std::string> complete_model_options(const Scene& scene) {
  std::vector<std::string> options;
  if (scene.lattice.kind == LatticeKind::random) options.emplace_back("random lattice");
  if (scene.strength && scene.strength->internal_friction > 0)
    options.emplace_back("internal friction");
  if (scene.contact && scene.contact->enabled && scene.contact->friction > 0)
    options.emplace_back("contact friction");
  if (scene.loading.basal_discontinuity) options.emplace_back("basal discontinuity");
  if (!scene.layers.empty()) options.emplace_back("layers");
  if (scene.heterogeneity && scene.heterogeneity->spread > 0) options.emplace_back("heterogeneity");
  return options;
}

std::string model_label(const Scene& scene) {
  const std::vector<std::string> options = complete_model_options(scene);
  if (options.empty()) return "the paper's model";
  // The complete model has the first four; fewer is the paper's model with some of them.
  const bool complete = std::ranges::all_of(
      std::array{"random lattice", "internal friction", "contact friction", "basal discontinuity"},
      [&](const char* core) { return std::ranges::find(options, core) != options.end(); });
  std::string label = complete ? "the complete model: " : "the paper's model with: ";
  for (std::size_t k = 0; k < options.size(); ++k) label += (k ? ", " : "") + options[k];
  return label;
}

}  // namespace latfrac
