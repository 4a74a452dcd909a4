// Size and memory estimates of a scene, from its lattice geometry and fitted factor growth.
#include "latfrac/size_estimate.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include "latfrac/lattice.h"

namespace latfrac {

SizeEstimate estimate_size(const Scene& scene) {
  const LatticeCount count = count_lattice(scene.lattice);
  SizeEstimate estimate;
  estimate.nodes = count.nodes;
  estimate.bonds = count.bonds;
  estimate.unknowns = count.nodes * scene.lattice.dim;
  const double n = static_cast<double>(estimate.unknowns);
  const double factor = scene.lattice.dim == 2 ? 7.1 * n * std::log(std::max(n, 2.0))
                                               : 15.6 * std::pow(n, 4.0 / 3.0);
  estimate.factor_nonzeros = static_cast<std::int64_t>(factor);
  estimate.memory_bytes = 24.0 * factor + 1024.0 * static_cast<double>(count.nodes);
  return estimate;
}

double available_memory_bytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  double kilobytes = 0;
  std::string unit;
  while (meminfo >> key >> kilobytes >> unit) {
    if (key == "MemAvailable:") return kilobytes * 1024.0;
  }
  return 0;
}

std::string describe(const SizeEstimate& e) {
  std::ostringstream text;
  text << "size estimate\n"
       << "  nodes            " << e.nodes << "\n"
       << "  bonds            " << e.bonds << "\n"
       << "  unknowns         " << e.unknowns << " (before supports)\n"
       << "  factor entries   " << static_cast<double>(e.factor_nonzeros) << "\n"
       << "  peak memory      " << e.memory_bytes / (1 << 20) << " MiB (estimate)\n";
  return text.str();
}

}  // namespace latfrac
