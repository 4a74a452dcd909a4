// Size and memory estimates of a scene, from its lattice geometry and fitted factor growth.
#include "latfrac/scene/size_estimate.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "latfrac/geometry/lattice.h"

namespace latfrac {

SizeEstimate estimate_size(const Scene& scene) {
  const LatticeSpec& spec = scene.lattice;
  // Counted in floating point from the geometry, so that an absurd scene cannot overflow
  // an integer.
  const double a = spec.spacing;
  const double rows =
      spec.size[2] / (spec.dim == 2 ? std::sqrt(3.0) / 2 * a : std::sqrt(2.0 / 3.0) * a) + 1;
  const double per_row = spec.size[0] / a + 1;
  const double columns = spec.dim == 2 ? 1.0 : spec.size[1] / (std::sqrt(3.0) / 2 * a) + 1;
  SizeEstimate estimate;
  estimate.nodes = rows * per_row * columns;
  // A random lattice has the regular one's number density (poisson_disk.h), so the same
  // count; its bonds are Delaunay edges, 3 per node in 2-D (Euler) and about 7.5 in 3-D
  // (15 neighbours inside), counted at 7.75.
  const bool random = spec.kind == LatticeKind::random;
  const double bonds_per_node =
      spec.dim == 2 ? 3.0 : random ? 7.75 : spec.next_nearest ? 9.0 : 6.0;
  estimate.bonds = bonds_per_node * estimate.nodes;
  estimate.unknowns = estimate.nodes * spec.dim;
  const double n = estimate.unknowns;
  estimate.factor_nonzeros =
      spec.dim == 2 ? 7.1 * n * std::log(std::max(n, 2.0)) : 15.6 * std::pow(n, 4.0 / 3.0);
  estimate.memory_bytes = 24.0 * estimate.factor_nonzeros + 1024.0 * estimate.nodes;
  return estimate;
}

namespace {
constexpr double mumps_bytes_per_entry = 10.7;
constexpr double rank_imbalance = 1.15;  // rank 0 holds more than its share
double replicated_bytes(const SizeEstimate& estimate) {
  return 45.0 * 1024 * 1024 + 10.0 * 1024 * estimate.nodes;
}
}  // namespace

double rank_memory_bytes(const SizeEstimate& estimate, int ranks) {
  const double factor = mumps_bytes_per_entry * estimate.factor_nonzeros;
  return replicated_bytes(estimate) +
         (ranks > 1 ? rank_imbalance * factor / ranks : factor);
}

std::string describe_ranks(const SizeEstimate& estimate, double available_bytes) {
  std::ostringstream text;
  text << "  petsc backend, peak memory per rank (estimate):";
  for (int ranks : {1, 2, 4, 8, 16, 32, 64})
    text << (ranks == 1 ? " " : ", ") << ranks << ": " << readable_bytes(rank_memory_bytes(estimate, ranks));
  text << "\n";
  if (available_bytes > 0) {
    const double whole = replicated_bytes(estimate);
    if (whole < available_bytes) {
      const double factor = mumps_bytes_per_entry * estimate.factor_nonzeros;
      const double ranks =
          rank_memory_bytes(estimate, 1) <= available_bytes
              ? 1.0
              : std::max(2.0, std::ceil(rank_imbalance * factor / (available_bytes - whole)));
      text << "  ranks needed with " << readable_bytes(available_bytes) << " each: " << ranks
           << " (one per machine; the factor is split, the model is on every rank)\n";
    } else {
      text << "  no number of ranks with " << readable_bytes(available_bytes)
           << " each holds it: what every rank holds whole does not fit\n";
    }
  }
  return text.str();
}

std::string readable_bytes(double bytes) {
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB"};
  int unit = 0;
  // From 1000 on, the next unit: three digits would print 1010 as "1.01e+03".
  while (bytes >= 1000 && unit < 5) {
    bytes /= 1024;
    ++unit;
  }
  std::ostringstream text;
  text << std::setprecision(bytes < 1e4 ? 3 : 2) << bytes << " " << units[unit];
  return text.str();
}

std::string memory_refusal(const Scene& scene, const SizeEstimate& estimate,
                           double available_bytes) {
  if (available_bytes <= 0 || estimate.memory_bytes <= available_bytes) return "";
  std::ostringstream text;
  text << scene.source_path << ": lattice.spacing: " << scene.lattice.spacing << " m makes ";
  // A lattice.size near 1e308 makes the estimate overflow: no count to print.
  if (std::isfinite(estimate.nodes) && std::isfinite(estimate.memory_bytes))
    text << "about " << std::setprecision(3) << estimate.nodes << " nodes needing about "
         << readable_bytes(estimate.memory_bytes);
  else
    text << "more nodes than a double counts (lattice.size over lattice.spacing overflows)";
  text << ", but only " << readable_bytes(available_bytes)
       << " are available; use a larger spacing or a smaller lattice.size (or --force to try "
          "anyway)";
  return text.str();
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
       << "  factor entries   " << e.factor_nonzeros << "\n"
       << "  peak memory      " << readable_bytes(e.memory_bytes) << " (estimate)\n";
  return text.str();
}

}  // namespace latfrac
