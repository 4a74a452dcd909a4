// The node fields of a snapshot: displacement, stress invariants, the largest failure index.
#include "latfrac/render/node_field.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "latfrac/base/error.h"

namespace latfrac {
namespace {

constexpr double no_value = std::numeric_limits<double>::quiet_NaN();

// J2 of a stress in Voigt order xx yy zz yz xz xy.
double second_invariant(const double* s) {
  const double mean = (s[0] + s[1] + s[2]) / 3;
  const double dx = s[0] - mean, dy = s[1] - mean, dz = s[2] - mean;
  return 0.5 * (dx * dx + dy * dy + dz * dz) + s[3] * s[3] + s[4] * s[4] + s[5] * s[5];
}

std::vector<double> largest_intact_failure_index(const RunResult& result,
                                                 const Snapshot& snapshot) {
  if (snapshot.bond_failure_index.size() != result.bond_count())
    throw InputError("render: field f needs bond_f of every bond; the snapshot has " +
                     std::to_string(snapshot.bond_failure_index.size()) + " values for " +
                     std::to_string(result.bond_count()) + " bonds");
  std::vector<double> values(result.node_count(), no_value);
  for (std::size_t bond = 0; bond < result.bond_count(); ++bond) {
    if (snapshot.bond_intact[bond] == 0) continue;
    for (int end = 0; end < 2; ++end) {
      double& value = values[result.bonds[2 * bond + end]];
      const double f = snapshot.bond_failure_index[bond];
      value = std::isnan(value) ? f : std::max(value, f);
    }
  }
  return values;
}

}  // namespace

FieldLabel field_label(NodeField field) {
  switch (field) {
    case NodeField::displacement: return {"|u|", "m", 1};
    case NodeField::ux: return {"u_x", "m", 1};
    case NodeField::uy: return {"u_y", "m", 1};
    case NodeField::uz: return {"u_z", "m", 1};
    case NodeField::sigma_xx: return {"σ_xx", "MPa", 1e-6};
    case NodeField::sigma_yy: return {"σ_yy", "MPa", 1e-6};
    case NodeField::sigma_zz: return {"σ_zz", "MPa", 1e-6};
    case NodeField::sigma_xz: return {"σ_xz", "MPa", 1e-6};
    case NodeField::sigma_mean: return {"mean stress", "MPa", 1e-6};
    case NodeField::von_mises: return {"von Mises stress", "MPa", 1e-6};
    case NodeField::sqrt_j2: return {"√J2", "MPa", 1e-6};
    case NodeField::failure_index: return {"failure index f", "", 1};
    case NodeField::none: break;
  }
  return {"", "", 1};
}

std::vector<double> node_field(const RunResult& result, const Snapshot& snapshot,
                               NodeField field) {
  const std::size_t nodes = result.node_count();
  if (field == NodeField::failure_index) return largest_intact_failure_index(result, snapshot);
  const bool stress = field >= NodeField::sigma_xx && field <= NodeField::sqrt_j2;
  if (stress && snapshot.node_stress.size() != 6 * nodes)
    throw InputError("render: field " + std::string(name_of(field)) +
                     " needs node_stress of every node; the snapshot has " +
                     std::to_string(snapshot.node_stress.size()) + " values for " +
                     std::to_string(nodes) + " nodes");
  std::vector<double> values(nodes, no_value);
  for (std::size_t node = 0; node < nodes; ++node) {
    const double* u = &snapshot.displacement[3 * node];
    const double* s = stress ? &snapshot.node_stress[6 * node] : nullptr;
    double& value = values[node];
    switch (field) {
      case NodeField::displacement: value = std::hypot(u[0], u[1], u[2]); break;
      case NodeField::ux: value = u[0]; break;
      case NodeField::uy: value = u[1]; break;
      case NodeField::uz: value = u[2]; break;
      case NodeField::sigma_xx: value = s[0]; break;
      case NodeField::sigma_yy: value = s[1]; break;
      case NodeField::sigma_zz: value = s[2]; break;
      case NodeField::sigma_xz: value = s[4]; break;
      case NodeField::sigma_mean: value = (s[0] + s[1] + s[2]) / 3; break;
      case NodeField::von_mises: value = std::sqrt(3 * second_invariant(s)); break;
      case NodeField::sqrt_j2: value = std::sqrt(second_invariant(s)); break;
      case NodeField::failure_index:
      case NodeField::none: break;
    }
  }
  return values;
}

}  // namespace latfrac
