// Threads for the sweeps over every bond (node stresses, residuals, the criterion's
// crossings and ranks). Each item is computed on its own and every sum keeps the serial
// order (docs/model.md, "Threads"), so a run gives the same numbers bit for bit on any
// number of threads.
//
// The count is LATFRAC_THREADS when set (1 runs everything on the calling thread), else
// the machine's cores; one under mpirun with more than one rank, where the ranks share
// the cores. CHOLMOD's and OpenBLAS's own threads are set apart (solvers/cholesky.cpp).
#pragma once

#include <cstdint>
#include <functional>

namespace latfrac::threads {

// The threads a sweep uses.
int count();
// Sets it for the rest of the process (0: back to LATFRAC_THREADS or the cores).
void set_count(int threads);

// The grains of the bond sweeps: waking a thread costs about as much as a few thousand
// bonds' work (docs/benchmarks.md, "Threads: the bond sweeps").
constexpr std::int64_t bond_grain = 4096, node_grain = 2048;

// The threads for_blocks(items, grain, ...) runs on: as many as have `grain` items each,
// at most count().
int used(std::int64_t items, std::int64_t grain);
// Runs body(first, last) on disjoint blocks that cover [0, items), in parallel on used()
// threads, four blocks per thread, each block taken by the next free thread; on the
// calling thread alone, as one block, when that is one thread. An exception thrown by a
// block is rethrown here.
void for_blocks(std::int64_t items, std::int64_t grain,
                const std::function<void(std::int64_t first, std::int64_t last)>& body);

}  // namespace latfrac::threads
