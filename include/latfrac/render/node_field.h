// A value on each node of a snapshot, for pictures: displacement, stress or failure index.
//
// Stresses come from the snapshot's node_stress (Voigt xx yy zz yz xz xy, Pa, tension
// positive). With s the deviatoric part of sigma, J2 = s:s / 2 and the von Mises stress is
// sqrt(3 J2). The failure index of a node is the largest f (bond_f) of its intact bonds:
// the bond nearest to breaking; a node without an intact bond has none (NaN).
#pragma once

#include <string>
#include <vector>

#include "latfrac/fracture/run_result.h"
#include "latfrac/scene/picture_options.h"

namespace latfrac {

// How a field is labelled: its title and the unit its values are shown in (`per_si`
// display units per SI unit: 1e-6 for stresses shown in MPa).
struct FieldLabel {
  std::string title;
  std::string unit;
  double per_si = 1;
};
FieldLabel field_label(NodeField field);

// The field's value at every node of `snapshot`, in SI units (NaN where it has none).
// Throws InputError when the snapshot lacks the data the field needs.
std::vector<double> node_field(const RunResult& result, const Snapshot& snapshot,
                               NodeField field);

}  // namespace latfrac
