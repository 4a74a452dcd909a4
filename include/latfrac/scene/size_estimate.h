// How big a scene is before it is built: nodes, bonds, unknowns, factor size and memory.
//
// Nodes and bonds are counted from the lattice geometry. The Cholesky factor's size
// follows nested-dissection scaling fitted to bench/bench_equilibrium on the paper's
// lattices: nnz(L) ~ 7.1 n ln n in 2-D and ~ 15.6 n^(4/3) in 3-D for n unknowns; peak
// memory is about 24 bytes per factor entry plus 1 kB per node.
#pragma once

#include <cstdint>
#include <string>

#include "latfrac/scene/scene.h"

namespace latfrac {

// Counts are doubles: an absurd scene must still give a finite, printable estimate.
struct SizeEstimate {
  double nodes = 0, bonds = 0, unknowns = 0, factor_nonzeros = 0;
  double memory_bytes = 0;
};

SizeEstimate estimate_size(const Scene& scene);

// The memory the operating system says is available now (MemAvailable), bytes; 0 if unknown.
double available_memory_bytes();

std::string describe(const SizeEstimate& estimate);

// Bytes in readable units: "512 MiB", "3.2 GiB", "1.1e+03 PiB".
std::string readable_bytes(double bytes);

// The refusal message when the estimate exceeds the available memory, or "" when it fits.
std::string memory_refusal(const Scene& scene, const SizeEstimate& estimate,
                           double available_bytes);

}  // namespace latfrac
