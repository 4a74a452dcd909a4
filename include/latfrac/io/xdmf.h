// The XDMF (.xmf) description that lets ParaView open a result file.
//
// The .xmf holds no numbers: it points into the .h5 written by write_result_file. Per
// snapshot it describes a spatial collection of two grids over the same points:
//   nodes  Polyvertex, point data displacement and node_stress;
//   bonds  Polyline of 2 nodes per bond, cell data bond_kind, bond_intact, bond_f, and
//          point data displacement so that Warp By Vector deforms the bonds;
// inside a temporal collection with Time = lambda. Without snapshots it describes the
// undeformed lattice, without time. docs/result-files.md shows how to use it in ParaView.
#pragma once

#include <string>

#include "latfrac/fracture/run_result.h"

namespace latfrac {

// Writes xmf_path atomically (via "<xmf_path>.partial"); throws Error if that fails.
// h5_file_name is how the .xmf names the .h5: relative to the .xmf, normally just the
// file name since the two sit side by side.
void write_xdmf(const std::string& xmf_path, const std::string& h5_file_name,
                const RunResult& result);

}  // namespace latfrac
