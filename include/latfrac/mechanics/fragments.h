// Parts of the body that a break leaves without support.
//
// The stiffness has no rotational null space (the shear springs resist rigid rotation,
// model.md section 2), so a connected part is supported when, along every axis, at least
// one of its nodes has a prescribed displacement. Breaking a bond can split its part in
// two; each side is checked. Connectivity runs over intact bonds and active contacts.
#pragma once

#include <cstdint>
#include <vector>

#include "latfrac/mechanics/model.h"

namespace latfrac {

class FragmentDetector {
 public:
  explicit FragmentDetector(const Model& model);

  // A part without support along some axes: its nodes, and the components (0 .. dim-1)
  // along which none of them is held.
  struct LoosePart {
    std::vector<std::int64_t> nodes;
    std::vector<int> free_components;
  };

  // With bond b already marked broken: every part the break left without support along
  // some axis (empty when the body is still held).
  std::vector<LoosePart> unsupported_after_break(const Model& model, std::int64_t bond) const;
  // Every unsupported part of the model (used at the start of a run).
  std::vector<LoosePart> unsupported_parts(const Model& model) const;

 private:
  bool connects(const Model& model, std::int64_t bond) const;
  std::vector<std::int64_t> component(const Model& model, std::int64_t start) const;
  std::vector<int> free_components(const Model& model,
                                   const std::vector<std::int64_t>& nodes) const;
  // Neighbours of each node with the bond that joins them.
  std::vector<std::vector<std::pair<std::int64_t, std::int64_t>>> neighbours_;
};

}  // namespace latfrac
