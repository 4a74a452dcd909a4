// The supports and contacts a run starts from.
#include "latfrac/fracture/initial_supports.h"

#include "latfrac/base/error.h"
#include "latfrac/mechanics/fragments.h"

namespace latfrac {

std::vector<FragmentEvent> prepare_supports(Model& model, const std::string& source_path) {
  ModelEditor editor(model);
  for (std::int64_t b = 0; b < model.lattice.bond_count(); ++b) {
    if (model.contact_capable(b)) editor.set_state(b, PairState::closed);
  }
  const FragmentDetector detector(model);
  const auto loose = detector.unsupported_parts(model);
  std::vector<FragmentEvent> events;
  for (const auto& part : loose) {
    if (static_cast<std::int64_t>(part.nodes.size()) == model.lattice.node_count()) {
      throw InputError(source_path +
                       ": [boundary]: the face conditions leave the body free to move "
                       "along an axis; hold at least one face along every axis");
    }
  }
  for (const auto& part : loose) {
    editor.hold(part.nodes, part.free_components, Vector::Zero(model.dofs().dof_count()));
    events.push_back({0.0, static_cast<std::int64_t>(part.nodes.size())});
  }
  return events;
}

}  // namespace latfrac
