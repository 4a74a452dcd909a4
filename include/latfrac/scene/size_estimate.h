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

// The petsc backend's peak memory on each of `ranks` ranks (docs/parallel.md): MUMPS's
// factor, about 10.7 bytes per (estimated) factor entry, split over the ranks with 15 %
// more on the busiest, plus what every rank holds whole (the model, latfrac's stiffness,
// CHOLMOD's symbolic analysis, the libraries): about 45 MiB + 10 KiB per node. Fitted to
// bench/bench_backend on the 3-D reference block at 1000 m and 700 m on 1 to 4 ranks
// (within 10 % of each measured peak).
double rank_memory_bytes(const SizeEstimate& estimate, int ranks);
// The table `latfrac check` prints for the petsc backend: memory per rank for 1 to 64
// ranks, and how many ranks of `available_bytes` each it needs.
std::string describe_ranks(const SizeEstimate& estimate, double available_bytes);

// The memory the operating system says is available now (MemAvailable), bytes; 0 if unknown.
double available_memory_bytes();

std::string describe(const SizeEstimate& estimate);

// Bytes in readable units: "512 MiB", "3.2 GiB", "1.1e+03 PiB".
std::string readable_bytes(double bytes);

// The refusal message when the estimate exceeds the available memory, or "" when it fits.
std::string memory_refusal(const Scene& scene, const SizeEstimate& estimate,
                           double available_bytes);

}  // namespace latfrac
