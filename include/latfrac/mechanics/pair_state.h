// The state of a pair of nodes joined in the lattice: an intact bond, or a broken one
// that is an open or a closed contact.
#pragma once

#include <cstdint>

namespace latfrac {

// intact: the bond's springs act (its bond law).
// open:   broken, and nothing acts (a contact that is apart, or a broken bond that cannot
//         touch: next-nearest, or a scene without contact).
// closed: broken, and its contact law acts (the faces touch); with friction, the contact
//         sticks (its tangential spring is anchored, friction_law.h).
// slip:   broken, closed and sliding: with friction, the tangential force is mu |Fn|
//         along the sense of sliding (in 3-D: on one facet of the polyhedral friction
//         cone, the force's component along the facet still sticking).
// slip_edge: 3-D only: closed and sliding with the tangential force on an edge of the
//         polyhedral cone (two facets at their limit), fixed at mu |Fn| along that edge.
enum class PairState : std::uint8_t { intact = 0, open = 1, closed = 2, slip = 3, slip_edge = 4 };

// Whether the pair is a sliding contact (its tangent is nonsymmetric).
inline bool slides(PairState state) {
  return state == PairState::slip || state == PairState::slip_edge;
}

// Whether the pair holds its two nodes together (intact, or a closed contact): what the
// fragment check follows.
inline bool connects(PairState state) { return state != PairState::open; }

}  // namespace latfrac
