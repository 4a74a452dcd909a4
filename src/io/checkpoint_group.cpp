// Writing and reading the /checkpoint group: the state a stopped run continues from.
#include "checkpoint_group.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "hdf5_arrays.h"
#include "latfrac/base/error.h"
#include "latfrac/mechanics/pair_state.h"

namespace latfrac {
namespace {

const std::string group = "/checkpoint";

std::string joined_lines(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) text += line + "\n";
  return text;
}

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream stream(text);
  for (std::string line; std::getline(stream, line);) lines.push_back(line);
  return lines;
}

hsize_t length_of(hid_t file, const std::string& path) {
  const hdf5::Shape shape = hdf5::dataset_shape(file, path);
  if (shape.size() != 1) throw InputError("dataset " + path + " is not a 1-D array");
  return shape[0];
}

// A lambda that may be "none" (EventSource::none, a NaN in memory): written as 0 with an
// attribute NAME_none = 1, so that no file holds a NaN (docs/robustness.md); older files
// that wrote the NaN itself read as before.
void write_optional_lambda(hid_t file, const char* name, double lambda) {
  const bool none = std::isnan(lambda);
  hdf5::write_attribute(file, group, name, none ? 0.0 : lambda);
  if (none)
    hdf5::write_attribute(file, group, (std::string(name) + "_none").c_str(), std::uint8_t{1});
}

double read_optional_lambda(hid_t file, const char* name) {
  const std::string flag = std::string(name) + "_none";
  if (hdf5::has_attribute(file, group, flag.c_str()) &&
      hdf5::read_attribute<std::uint8_t>(file, group, flag.c_str()) != 0)
    return std::numeric_limits<double>::quiet_NaN();
  return hdf5::read_attribute<double>(file, group, name);
}

}  // namespace

void write_checkpoint_group(hid_t file, const RunCheckpoint& c) {
  hdf5::create_group(file, group);
  hdf5::write_attribute(file, group, "started", static_cast<std::uint8_t>(c.started));
  hdf5::write_attribute(file, group, "lambda", c.lambda);
  hdf5::write_attribute(file, group, "next_step", c.next_step);
  hdf5::write_attribute(file, group, "cascade", c.cascade);
  hdf5::write_attribute(file, group, "state_lambda", c.state_lambda);
  hdf5::write_attribute(file, group, "state_valid", static_cast<std::uint8_t>(c.state_valid));
  hdf5::write_attribute(file, group, "snapshots_taken", c.snapshots_taken);
  hdf5::write_attribute(file, group, "next_cascade", c.next_cascade);
  hdf5::write_attribute(file, group, "fragments_at_start", c.fragments_at_start);
  write_optional_lambda(file, "switch_lambda", c.switches.lambda);
  hdf5::write_attribute(file, group, "switch_at_start",
                        static_cast<std::uint8_t>(c.switches.switch_at_start));
  hdf5::write_string_attribute(file, group, "problem_path", c.problem_path);
  hdf5::write_string_attribute(file, group, "overrides", joined_lines(c.overrides));
  hdf5::write_dataset(file, group + "/pair_state", c.pair_states, {c.pair_states.size()});
  if (!c.contact_memory.empty()) {
    hdf5::write_dataset(file, group + "/contact_memory", c.contact_memory,
                        {c.pair_states.size(), RunCheckpoint::memory_values});
  }
  if (!c.contact_normals.empty()) {
    hdf5::write_dataset(file, group + "/contact_normal", c.contact_normals,
                        {c.pair_states.size(), 3});
  }
  hdf5::write_dataset(file, group + "/free_index", c.free_index, {c.free_index.size()});
  hdf5::write_dataset(file, group + "/prescribed_base", c.prescribed_base,
                      {c.prescribed_base.size()});
  hdf5::write_dataset(file, group + "/prescribed_rate", c.prescribed_rate,
                      {c.prescribed_rate.size()});
  hdf5::write_dataset(file, group + "/free_state", c.free_state, {c.free_state.size()});
  const EquilibriumSolver::History& factor = c.factor;
  hdf5::write_attribute(file, group, "factor_current",
                        static_cast<std::uint8_t>(factor.factor_current));
  hdf5::write_attribute(file, group, "solution_valid",
                        static_cast<std::uint8_t>(factor.solution_valid));
  hdf5::write_attribute(file, group, "solution_lambda", factor.solution_lambda);
  hdf5::write_dataset(file, group + "/factored_states", factor.factored_states,
                      {factor.factored_states.size()});
  std::vector<std::int64_t> change_bond, pending_index;
  std::vector<std::uint8_t> change_state;
  std::vector<double> pending_value;
  for (const auto& [bond, state] : factor.changes) {
    change_bond.push_back(bond);
    change_state.push_back(state);
  }
  for (const auto& [index, value] : factor.pending_forces) {
    pending_index.push_back(index);
    pending_value.push_back(value);
  }
  hdf5::write_dataset(file, group + "/change_bond", change_bond, {change_bond.size()});
  hdf5::write_dataset(file, group + "/change_state", change_state, {change_state.size()});
  const std::vector<double> solution(factor.solution.data(),
                                     factor.solution.data() + factor.solution.size());
  hdf5::write_dataset(file, group + "/solution", solution, {solution.size()});
  hdf5::write_dataset(file, group + "/pending_index", pending_index, {pending_index.size()});
  hdf5::write_dataset(file, group + "/pending_value", pending_value, {pending_value.size()});
  hdf5::write_dataset(file, group + "/elimination_order", factor.elimination_order,
                      {factor.elimination_order.size()});
  if (factor.lu_current) {
    hdf5::write_dataset(file, group + "/lu_states", factor.lu_states, {factor.lu_states.size()});
    hdf5::write_dataset(file, group + "/lu_directions", factor.lu_directions,
                        {factor.lu_directions.size()});
    hdf5::write_dataset(file, group + "/lu_change_bond", factor.lu_change_bonds,
                        {factor.lu_change_bonds.size()});
    hdf5::write_dataset(file, group + "/lu_change_value", factor.lu_change_values,
                        {factor.lu_change_values.size()});
  }
  if (!factor.woodbury_bonds.empty()) {
    const hsize_t k = factor.woodbury_bonds.size();
    hdf5::write_dataset(file, group + "/woodbury_bond", factor.woodbury_bonds, {k});
    hdf5::write_dataset(file, group + "/woodbury_term_count", factor.woodbury_term_counts, {k});
    hdf5::write_dataset(file, group + "/woodbury_term", factor.woodbury_terms,
                        {factor.woodbury_terms.size()});
    hdf5::write_dataset(file, group + "/woodbury_w", factor.woodbury_w,
                        {k, factor.woodbury_w.size() / k});
  }
  if (!factor.woodbury_bonds.empty() || !factor.path_y.empty()) {
    hdf5::write_attribute(file, group, "woodbury_pending_updates",
                          factor.woodbury_pending_updates);
    hdf5::write_dataset(file, group + "/woodbury_pending_start", factor.woodbury_pending_start,
                        {factor.woodbury_pending_start.size()});
    hdf5::write_dataset(file, group + "/woodbury_pending_index", factor.woodbury_pending_index,
                        {factor.woodbury_pending_index.size()});
    hdf5::write_dataset(file, group + "/woodbury_pending_value", factor.woodbury_pending_value,
                        {factor.woodbury_pending_value.size()});
    hdf5::write_dataset(file, group + "/woodbury_pending_sign", factor.woodbury_pending_sign,
                        {factor.woodbury_pending_sign.size()});
  }
  if (!factor.path_y.empty()) {
    const hsize_t n = factor.path_y.size() / 2;
    hdf5::write_dataset(file, group + "/path_y", factor.path_y, {2, n});
    hdf5::write_dataset(file, group + "/path_loads", factor.path_loads, {2, n});
  }

  const hsize_t bonds = c.pair_states.size();
  std::vector<std::uint8_t> sets;
  for (const std::string& set : c.switches.sets) sets.insert(sets.end(), set.begin(), set.end());
  hdf5::write_dataset(file, group + "/switch_sets", sets, {c.switches.sets.size(), bonds});
  // Friction's unstable-contact guard (absent in files without friction).
  if (!c.switches.stuck_bonds.empty() || !c.switches.unstable.empty()) {
    write_optional_lambda(file, "unstable_lambda", c.switches.unstable_lambda);
    hdf5::write_dataset(file, group + "/stuck_bond", c.switches.stuck_bonds,
                        {c.switches.stuck_bonds.size()});
    hdf5::write_dataset(file, group + "/stuck_lambda", c.switches.stuck_lambdas,
                        {c.switches.stuck_lambdas.size()});
    hdf5::write_dataset(file, group + "/unstable_bond", c.switches.unstable,
                        {c.switches.unstable.size()});
  }
}

namespace {

// What the checkpoint says of itself must hold before any of it is used: every bond, dof
// and state named in range, every count non-negative, every lambda finite. A file damaged
// in a way its checksums cannot see (or edited) is refused here, where it would index
// out of range on resuming (docs/restart.md).
void check_checkpoint(const RunCheckpoint& c) {
  const auto bonds = static_cast<std::int64_t>(c.pair_states.size());
  auto refuse = [](const std::string& what) {
    throw InputError("the checkpoint " + what + ": the file is damaged");
  };
  auto in_range = [&](const std::vector<std::int64_t>& values, std::int64_t end, const char* name,
                      const char* of) {
    for (const std::int64_t v : values)
      if (v < 0 || v >= end)
        refuse(std::string("names ") + name + " " + std::to_string(v) + " of " +
               std::to_string(end) + " " + of);
  };
  auto states = [&](const std::vector<std::uint8_t>& values, const char* name) {
    for (const std::uint8_t v : values)
      if (v > static_cast<std::uint8_t>(PairState::slip_edge))
        refuse(std::string("has pair state ") + std::to_string(v) + " in " + name);
  };
  states(c.pair_states, "pair_state");
  states(c.factor.factored_states, "factored_states");
  states(c.factor.lu_states, "lu_states");
  std::int64_t next_free = 0;
  for (const std::int64_t index : c.free_index) {
    if (index == -1) continue;
    if (index != next_free) refuse("numbers its free degrees of freedom out of order");
    ++next_free;
  }
  const std::int64_t free = next_free;
  const auto state_size = static_cast<std::int64_t>(c.free_state.size());
  if (state_size != 0 && state_size != free)
    refuse("has " + std::to_string(state_size) + " state values for " + std::to_string(free) +
           " free degrees of freedom");
  std::vector<std::int64_t> changed;
  for (const auto& [bond, state] : c.factor.changes) {
    changed.push_back(bond);
    states({state}, "change_state");
  }
  in_range(changed, bonds, "bond", "bonds in its changes");
  in_range(c.factor.lu_change_bonds, bonds, "bond", "bonds in lu_change_bond");
  in_range(c.factor.woodbury_bonds, bonds, "bond", "bonds in woodbury_bond");
  in_range(c.switches.stuck_bonds, bonds, "bond", "bonds in stuck_bond");
  in_range(c.switches.unstable, bonds, "bond", "bonds in unstable_bond");
  std::vector<std::int64_t> rows;
  for (const auto& [row, value] : c.factor.pending_forces) rows.push_back(row);
  in_range(rows, free, "free dof", "in pending_index");
  in_range(c.factor.woodbury_pending_index, free, "free dof", "in woodbury_pending_index");
  if (!c.factor.elimination_order.empty()) {
    in_range(c.factor.elimination_order, free, "free dof", "in elimination_order");
    std::vector<char> seen(static_cast<std::size_t>(free), 0);
    for (const std::int64_t v : c.factor.elimination_order) seen[static_cast<std::size_t>(v)] = 1;
    if (static_cast<std::int64_t>(c.factor.elimination_order.size()) != free ||
        std::find(seen.begin(), seen.end(), 0) != seen.end())
      refuse("has an elimination order that is not a permutation of its free dofs");
  }
  const auto& starts = c.factor.woodbury_pending_start;
  for (std::size_t i = 0; i < starts.size(); ++i)
    if (starts[i] < (i == 0 ? 0 : starts[i - 1]) ||
        starts[i] > static_cast<std::int64_t>(c.factor.woodbury_pending_index.size()))
      refuse("has woodbury_pending_start out of order");
  if (c.factor.solution.size() != 0 && c.factor.solution.size() != free)
    refuse("has a solution of " + std::to_string(c.factor.solution.size()) + " values for " +
           std::to_string(free) + " free dofs");
  if (c.next_step < 0 || c.cascade < -1 || c.snapshots_taken < 0 || c.next_cascade < 0 ||
      c.fragments_at_start < 0 || c.factor.woodbury_pending_updates < 0)
    refuse(
        "has a negative count (next_step, cascade, snapshots_taken, next_cascade, "
        "fragments_at_start or woodbury_pending_updates)");
  if (!std::isfinite(c.lambda) || !std::isfinite(c.state_lambda) ||
      !std::isfinite(c.factor.solution_lambda))
    refuse("has a lambda that is not a finite number");
}

}  // namespace

RunCheckpoint read_checkpoint_group(hid_t file) {
  hdf5::require(file, group, "group");
  RunCheckpoint c;
  c.started = hdf5::read_attribute<std::uint8_t>(file, group, "started") != 0;
  c.lambda = hdf5::read_attribute<double>(file, group, "lambda");
  c.next_step = hdf5::read_attribute<std::int64_t>(file, group, "next_step");
  c.cascade = hdf5::read_attribute<std::int64_t>(file, group, "cascade");
  c.state_lambda = hdf5::read_attribute<double>(file, group, "state_lambda");
  c.state_valid = hdf5::read_attribute<std::uint8_t>(file, group, "state_valid") != 0;
  c.snapshots_taken = hdf5::read_attribute<std::int64_t>(file, group, "snapshots_taken");
  c.next_cascade = hdf5::read_attribute<std::int64_t>(file, group, "next_cascade");
  c.fragments_at_start = hdf5::read_attribute<std::int64_t>(file, group, "fragments_at_start");
  c.switches.lambda = read_optional_lambda(file, "switch_lambda");
  c.switches.switch_at_start =
      hdf5::read_attribute<std::uint8_t>(file, group, "switch_at_start") != 0;
  c.problem_path = hdf5::read_string_attribute(file, group, "problem_path");
  c.overrides = split_lines(hdf5::read_string_attribute(file, group, "overrides"));
  const hsize_t bonds = length_of(file, group + "/pair_state");
  const hsize_t dofs = length_of(file, group + "/free_index");
  c.pair_states = hdf5::read_dataset<std::uint8_t>(file, group + "/pair_state", {bonds});
  if (hdf5::exists(file, group + "/contact_memory")) {
    c.contact_memory = hdf5::read_dataset<double>(file, group + "/contact_memory",
                                                  {bonds, RunCheckpoint::memory_values});
  }
  if (hdf5::exists(file, group + "/contact_normal"))
    c.contact_normals = hdf5::read_dataset<double>(file, group + "/contact_normal", {bonds, 3});
  c.free_index = hdf5::read_dataset<std::int64_t>(file, group + "/free_index", {dofs});
  c.prescribed_base = hdf5::read_dataset<double>(file, group + "/prescribed_base", {dofs});
  c.prescribed_rate = hdf5::read_dataset<double>(file, group + "/prescribed_rate", {dofs});
  const hsize_t free = length_of(file, group + "/free_state");
  c.free_state = hdf5::read_dataset<double>(file, group + "/free_state", {free});
  EquilibriumSolver::History& factor = c.factor;
  factor.factor_current = hdf5::read_attribute<std::uint8_t>(file, group, "factor_current") != 0;
  factor.solution_valid = hdf5::read_attribute<std::uint8_t>(file, group, "solution_valid") != 0;
  factor.solution_lambda = hdf5::read_attribute<double>(file, group, "solution_lambda");
  factor.factored_states = hdf5::read_dataset<std::uint8_t>(
      file, group + "/factored_states", {length_of(file, group + "/factored_states")});
  const hsize_t changes = length_of(file, group + "/change_bond");
  const auto change_bond =
      hdf5::read_dataset<std::int64_t>(file, group + "/change_bond", {changes});
  const auto change_state =
      hdf5::read_dataset<std::uint8_t>(file, group + "/change_state", {changes});
  for (hsize_t i = 0; i < changes; ++i) factor.changes.push_back({change_bond[i], change_state[i]});
  const auto solution =
      hdf5::read_dataset<double>(file, group + "/solution", {length_of(file, group + "/solution")});
  factor.solution =
      Eigen::Map<const Vector>(solution.data(), static_cast<Eigen::Index>(solution.size()));
  const hsize_t pending = length_of(file, group + "/pending_index");
  const auto pending_index =
      hdf5::read_dataset<std::int64_t>(file, group + "/pending_index", {pending});
  const auto pending_value = hdf5::read_dataset<double>(file, group + "/pending_value", {pending});
  for (hsize_t i = 0; i < pending; ++i)
    factor.pending_forces.push_back({pending_index[i], pending_value[i]});
  if (hdf5::exists(file, group + "/elimination_order")) {
    factor.elimination_order = hdf5::read_dataset<std::int64_t>(
        file, group + "/elimination_order", {length_of(file, group + "/elimination_order")});
  }

  auto whole = [&](const std::string& name) { return hsize_t{length_of(file, group + name)}; };
  if (hdf5::exists(file, group + "/lu_states")) {
    factor.lu_current = true;
    factor.lu_states = hdf5::read_dataset<std::uint8_t>(file, group + "/lu_states", {whole("/lu_states")});
    factor.lu_directions =
        hdf5::read_dataset<double>(file, group + "/lu_directions", {whole("/lu_directions")});
    factor.lu_change_bonds = hdf5::read_dataset<std::int64_t>(file, group + "/lu_change_bond",
                                                              {whole("/lu_change_bond")});
    factor.lu_change_values = hdf5::read_dataset<double>(file, group + "/lu_change_value",
                                                         {whole("/lu_change_value")});
  }
  if (hdf5::exists(file, group + "/woodbury_bond")) {
    factor.woodbury_bonds =
        hdf5::read_dataset<std::int64_t>(file, group + "/woodbury_bond", {whole("/woodbury_bond")});
    factor.woodbury_term_counts = hdf5::read_dataset<std::int64_t>(
        file, group + "/woodbury_term_count", {whole("/woodbury_term_count")});
    factor.woodbury_terms =
        hdf5::read_dataset<double>(file, group + "/woodbury_term", {whole("/woodbury_term")});
    const hdf5::Shape w_shape = hdf5::dataset_shape(file, group + "/woodbury_w");
    if (w_shape.size() != 2 || w_shape[0] != factor.woodbury_bonds.size())
      throw InputError("dataset " + group + "/woodbury_w is " + hdf5::shape_text(w_shape) +
                       ", expected " + std::to_string(factor.woodbury_bonds.size()) + " x ?");
    factor.woodbury_w = hdf5::read_dataset<double>(file, group + "/woodbury_w", w_shape);
  }
  if (hdf5::exists(file, group + "/woodbury_pending_start")) {
    factor.woodbury_pending_updates =
        hdf5::read_attribute<std::int64_t>(file, group, "woodbury_pending_updates");
    factor.woodbury_pending_start = hdf5::read_dataset<std::int64_t>(
        file, group + "/woodbury_pending_start", {whole("/woodbury_pending_start")});
    factor.woodbury_pending_index = hdf5::read_dataset<std::int64_t>(
        file, group + "/woodbury_pending_index", {whole("/woodbury_pending_index")});
    factor.woodbury_pending_value = hdf5::read_dataset<double>(
        file, group + "/woodbury_pending_value", {whole("/woodbury_pending_value")});
    factor.woodbury_pending_sign = hdf5::read_dataset<double>(
        file, group + "/woodbury_pending_sign", {whole("/woodbury_pending_sign")});
  }
  if (hdf5::exists(file, group + "/path_y")) {
    for (const char* name : {"/path_y", "/path_loads"}) {
      const hdf5::Shape shape = hdf5::dataset_shape(file, group + name);
      if (shape.size() != 2 || shape[0] != 2)
        throw InputError("dataset " + group + name + " is " + hdf5::shape_text(shape) +
                         ", expected 2 x ?");
      (std::string(name) == "/path_y" ? factor.path_y : factor.path_loads) =
          hdf5::read_dataset<double>(file, group + name, shape);
    }
  }

  const hdf5::Shape sets_shape = hdf5::dataset_shape(file, group + "/switch_sets");
  if (sets_shape.size() != 2 || sets_shape[1] != bonds)
    throw InputError("dataset " + group + "/switch_sets is " + hdf5::shape_text(sets_shape) +
                     ", expected ? x " + std::to_string(bonds));
  const auto sets = hdf5::read_dataset<std::uint8_t>(file, group + "/switch_sets", sets_shape);
  for (hsize_t i = 0; i < sets_shape[0]; ++i)
    c.switches.sets.emplace_back(sets.begin() + i * bonds, sets.begin() + (i + 1) * bonds);
  if (hdf5::exists(file, group + "/stuck_bond")) {
    c.switches.unstable_lambda = read_optional_lambda(file, "unstable_lambda");
    c.switches.stuck_bonds = hdf5::read_dataset<std::int64_t>(
        file, group + "/stuck_bond", {length_of(file, group + "/stuck_bond")});
    c.switches.stuck_lambdas = hdf5::read_dataset<double>(
        file, group + "/stuck_lambda", {length_of(file, group + "/stuck_lambda")});
    c.switches.unstable = hdf5::read_dataset<std::int64_t>(
        file, group + "/unstable_bond", {length_of(file, group + "/unstable_bond")});
    if (c.switches.stuck_bonds.size() != c.switches.stuck_lambdas.size())
      throw InputError("datasets " + group + "/stuck_bond and stuck_lambda differ in length");
  }
  check_checkpoint(c);
  return c;
}

}  // namespace latfrac
