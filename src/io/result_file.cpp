// Writing a RunResult to an HDF5 result file and reading it back (layout: docs/result-files.md).
#include "latfrac/io/result_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <numeric>
#include <system_error>

#include "checkpoint_group.h"
#include "hdf5_arrays.h"
#include "hdf5_handles.h"
#include "latfrac/base/atomic_write.h"
#include "latfrac/base/error.h"

namespace latfrac {

namespace {

using hdf5::Shape;

std::string snapshot_group(std::size_t index) { return "/snapshots/" + std::to_string(index); }

void require_size(std::size_t actual, std::size_t expected, const std::string& what) {
  if (actual != expected) {
    throw Error("cannot write an inconsistent RunResult: " + what + " has " +
                std::to_string(actual) + " values, expected " + std::to_string(expected));
  }
}

void check_sizes(const RunResult& result) {
  if (result.positions.size() % 3 != 0) {
    throw Error("cannot write an inconsistent RunResult: positions has " +
                std::to_string(result.positions.size()) + " values, not a multiple of 3");
  }
  const std::size_t nodes = result.node_count();
  const std::size_t bonds = result.bond_count();
  require_size(result.bonds.size(), 2 * bonds, "bonds (M x 2)");
  for (std::size_t i = 0; i < result.snapshots.size(); ++i) {
    const Snapshot& snapshot = result.snapshots[i];
    const std::string name = "snapshot " + std::to_string(i) + " ";
    require_size(snapshot.displacement.size(), 3 * nodes, name + "displacement (N x 3)");
    require_size(snapshot.bond_intact.size(), bonds, name + "bond_intact (M)");
    require_size(snapshot.bond_failure_index.size(), bonds, name + "bond_f (M)");
    require_size(snapshot.node_stress.size(), 6 * nodes, name + "node_stress (N x 6)");
  }
}

// Where the result first holds a value that is not a finite number: "inf in snapshot 0
// displacement (entry 12)", or nothing.
std::optional<std::string> first_non_finite(const RunResult& result) {
  std::optional<std::string> found;
  auto check = [&](const std::vector<double>& values, const std::string& what) {
    if (found) return;
    const auto bad = std::find_if(values.begin(), values.end(),
                                  [](double v) { return !std::isfinite(v); });
    if (bad != values.end())
      found = std::to_string(*bad) + " in " + what + " (entry " +
              std::to_string(bad - values.begin()) + ")";
  };
  check(result.positions, "lattice/positions");
  for (std::size_t i = 0; i < result.events.size(); ++i) {
    check({result.events[i].lambda, result.events[i].failure_index},
          "events (event " + std::to_string(i) + ")");
  }
  for (const FragmentEvent& fragment : result.fragments) check({fragment.lambda}, "fragments");
  for (std::size_t i = 0; i < result.snapshots.size(); ++i) {
    const Snapshot& snapshot = result.snapshots[i];
    const std::string name = "snapshot " + std::to_string(i) + " ";
    check({snapshot.lambda}, name + "lambda");
    check(snapshot.displacement, name + "displacement");
    check(snapshot.bond_failure_index, name + "bond_f");
    check(snapshot.node_stress, name + "node_stress");
  }
  return found;
}

}  // namespace

// The last guard of "no NaN in the output": a result with a value that is not a finite
// number is not written at all. Solvers check their residuals, so this means a bug.
void check_result_finite(const RunResult& result) {
  if (const auto bad = first_non_finite(result))
    throw Error("refusing to write a result with " + *bad +
                ": this is a bug in latfrac; please report it with the problem file");
}

namespace {

void write_provenance(hid_t file, const Provenance& provenance) {
  const std::string group = "/provenance";
  hdf5::create_group(file, group);
  hdf5::write_string_attribute(file, group, "software", provenance.software);
  hdf5::write_string_attribute(file, group, "version", provenance.version);
  hdf5::write_string_attribute(file, group, "git_commit", provenance.git_commit);
  hdf5::write_string_attribute(file, group, "command_line", provenance.command_line);
  hdf5::write_string_attribute(file, group, "problem", provenance.problem);
  hdf5::write_string_attribute(file, group, "created", provenance.created);
  hdf5::write_attribute(file, group, "seed", provenance.seed);
}

void write_scene(hid_t file, const SceneInfo& scene) {
  const std::string group = "/scene";
  hdf5::create_group(file, group);
  hdf5::write_string_attribute(file, group, "name", scene.name);
  hdf5::write_string_attribute(file, group, "criterion", scene.criterion);
  hdf5::write_attribute(file, group, "dim", scene.dim);
  hdf5::write_attribute(file, group, "spacing", scene.spacing);
  hdf5::write_attribute(file, group, "exaggeration", scene.exaggeration);
  if (!scene.model.empty()) hdf5::write_string_attribute(file, group, "model", scene.model);
}

// node_index (0 .. N-1) is not part of RunResult: it is the connectivity of the XDMF
// Polyvertex topology, which ParaView's XDMF 3 reader needs spelled out.
void write_lattice(hid_t file, const RunResult& result) {
  const hsize_t nodes = result.node_count();
  const hsize_t bonds = result.bond_count();
  hdf5::create_group(file, "/lattice");
  hdf5::write_dataset(file, "/lattice/positions", result.positions, {nodes, 3});
  hdf5::write_dataset(file, "/lattice/bonds", result.bonds, {bonds, 2});
  hdf5::write_dataset(file, "/lattice/bond_kind", result.bond_kind, {bonds});
  std::vector<std::int64_t> node_index(nodes);
  std::iota(node_index.begin(), node_index.end(), 0);
  hdf5::write_dataset(file, "/lattice/node_index", node_index, {nodes});
}

void write_events(hid_t file, const std::vector<BreakEvent>& events) {
  std::vector<double> lambda, failure_index;
  std::vector<std::int64_t> bond, cascade;
  std::vector<std::int8_t> mode;
  for (const BreakEvent& event : events) {
    lambda.push_back(event.lambda);
    bond.push_back(event.bond);
    failure_index.push_back(event.failure_index);
    mode.push_back(static_cast<std::int8_t>(event.mode));
    cascade.push_back(event.cascade);
  }
  const Shape shape{events.size()};
  hdf5::create_group(file, "/events");
  hdf5::write_dataset(file, "/events/lambda", lambda, shape);
  hdf5::write_dataset(file, "/events/bond", bond, shape);
  hdf5::write_dataset(file, "/events/f", failure_index, shape);
  hdf5::write_dataset(file, "/events/mode", mode, shape);
  hdf5::write_dataset(file, "/events/cascade", cascade, shape);
}

void write_fragments(hid_t file, const std::vector<FragmentEvent>& fragments) {
  std::vector<double> lambda;
  std::vector<std::int64_t> nodes;
  for (const FragmentEvent& fragment : fragments) {
    lambda.push_back(fragment.lambda);
    nodes.push_back(fragment.nodes);
  }
  const Shape shape{fragments.size()};
  hdf5::create_group(file, "/fragments");
  hdf5::write_dataset(file, "/fragments/lambda", lambda, shape);
  hdf5::write_dataset(file, "/fragments/nodes", nodes, shape);
}

void write_snapshots(hid_t file, const RunResult& result) {
  const hsize_t nodes = result.node_count();
  const hsize_t bonds = result.bond_count();
  hdf5::create_group(file, "/snapshots");
  for (std::size_t i = 0; i < result.snapshots.size(); ++i) {
    const Snapshot& snapshot = result.snapshots[i];
    const std::string group = snapshot_group(i);
    hdf5::create_group(file, group);
    hdf5::write_attribute(file, group, "lambda", snapshot.lambda);
    hdf5::write_dataset(file, group + "/displacement", snapshot.displacement, {nodes, 3});
    hdf5::write_dataset(file, group + "/bond_intact", snapshot.bond_intact, {bonds});
    hdf5::write_dataset(file, group + "/bond_f", snapshot.bond_failure_index, {bonds});
    hdf5::write_dataset(file, group + "/node_stress", snapshot.node_stress, {nodes, 6});
  }
}

void write_summary(hid_t file, const RunSummary& summary) {
  const std::string group = "/summary";
  hdf5::create_group(file, group);
  hdf5::write_attribute(file, group, "breaks", summary.breaks);
  hdf5::write_attribute(file, group, "solves", summary.solves);
  hdf5::write_attribute(file, group, "factorizations", summary.factorizations);
  hdf5::write_attribute(file, group, "factor_updates", summary.factor_updates);
  hdf5::write_attribute(file, group, "contact_cycles", summary.contact_cycles);
  hdf5::write_attribute(file, group, "relaxation_sweeps", summary.relaxation_sweeps);
  hdf5::write_attribute(file, group, "relaxation_unconverged", summary.relaxation_unconverged);
  hdf5::write_attribute(file, group, "floor_acceptances", summary.floor_acceptances);
  hdf5::write_attribute(file, group, "final_lambda", summary.final_lambda);
  hdf5::write_attribute(file, group, "wall_seconds", summary.wall_seconds);
  hdf5::write_attribute(file, group, "complete", static_cast<std::uint8_t>(summary.complete));
  hdf5::write_attribute(file, group, "contact_slip", summary.contact_slip);
  hdf5::write_attribute(file, group, "friction_work", summary.friction_work);
}

// With friction, per bond: the slip of its contact and the work its friction dissipated.
void write_friction(hid_t file, const RunResult& result) {
  if (result.contact_slip.empty()) return;
  hdf5::create_group(file, "/friction");
  const Shape shape{result.contact_slip.size()};
  hdf5::write_dataset(file, "/friction/slip", result.contact_slip, shape);
  hdf5::write_dataset(file, "/friction/work", result.friction_work, shape);
}

// With contacts along cracks, per bond: the normal its contact acts along.
void write_contact_normals(hid_t file, const RunResult& result) {
  if (result.contact_normal.empty()) return;
  hdf5::create_group(file, "/contact");
  hdf5::write_dataset(file, "/contact/normal", result.contact_normal,
                      {result.contact_normal.size() / 3, 3});
}

// A generous guess of the file's size, so that the in-memory file grows once.
std::size_t estimated_bytes(const RunResult& result) {
  const std::size_t nodes = result.node_count(), bonds = result.bond_count();
  const std::size_t per_snapshot = 8 * 9 * nodes + 9 * bonds;
  return 8 * 4 * nodes + 17 * bonds + 40 * result.events.size() +
         result.snapshots.size() * per_snapshot + 20 * bonds + 40 * nodes + (1 << 20);
}

// Writes bytes to a new file, synced to disk when asked; Error naming the file and the
// system's reason (a full disk, a file-size limit) when that fails.
void write_bytes(const std::string& file_name, const std::vector<char>& bytes, bool sync) {
  const int descriptor = ::open(file_name.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (descriptor < 0) throw Error("cannot create '" + file_name + "': " + std::strerror(errno));
  std::size_t written = 0;
  while (written < bytes.size()) {
    const ssize_t n = ::write(descriptor, bytes.data() + written, bytes.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int reason = errno;
      ::close(descriptor);
      throw Error("cannot write '" + file_name + "': " + std::strerror(reason));
    }
    written += static_cast<std::size_t>(n);
  }
  if (sync && ::fsync(descriptor) != 0) {
    const int reason = errno;
    ::close(descriptor);
    throw Error("cannot sync '" + file_name + "' to disk: " + std::strerror(reason));
  }
  if (::close(descriptor) != 0)
    throw Error("cannot write '" + file_name + "': " + std::strerror(errno));
}

// The file is built in memory (HDF5's core driver, no backing store) and written to disk
// in one piece by write_bytes: a full disk is then an error of one write() with the
// system's message, and HDF5 is never left holding a file it cannot flush.
void write_hdf5(const std::string& file_name, const RunResult& result,
                const RunCheckpoint* checkpoint) {
  const std::string quoted = "'" + file_name + "'";
  std::vector<char> image;
  {
    hdf5::Handle access = hdf5::checked(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "H5Pcreate", quoted);
    // SEMI: closing fails if an object is still open, instead of silently deferring it.
    hdf5::check(H5Pset_fclose_degree(access.get(), H5F_CLOSE_SEMI), "H5Pset_fclose_degree", quoted);
    hdf5::check(H5Pset_fapl_core(access.get(), estimated_bytes(result), 0), "H5Pset_fapl_core",
                quoted);
    // The 1.10 format: the superblock, object headers and chunk indexes carry checksums,
    // so a damaged attribute (the checkpoint's counters) fails to read instead of reading
    // wrong; any HDF5 since 1.10 (2016) reads it (docs/result-files.md).
    hdf5::check(H5Pset_libver_bounds(access.get(), H5F_LIBVER_V110, H5F_LIBVER_V110),
                "H5Pset_libver_bounds", quoted);
    hdf5::Handle file =
        hdf5::checked(H5Fcreate(file_name.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access.get()),
                      H5Fclose, "H5Fcreate", quoted);
    write_provenance(file.get(), result.provenance);
    write_scene(file.get(), result.scene);
    write_lattice(file.get(), result);
    write_events(file.get(), result.events);
    write_fragments(file.get(), result.fragments);
    write_snapshots(file.get(), result);
    write_summary(file.get(), result.summary);
    write_friction(file.get(), result);
    write_contact_normals(file.get(), result);
    if (checkpoint) write_checkpoint_group(file.get(), *checkpoint);
    hdf5::check(H5Fflush(file.get(), H5F_SCOPE_LOCAL), "H5Fflush", quoted);
    const ssize_t size = H5Fget_file_image(file.get(), nullptr, 0);
    if (size < 0) hdf5::fail("H5Fget_file_image", quoted);
    image.resize(static_cast<std::size_t>(size));
    if (H5Fget_file_image(file.get(), image.data(), image.size()) < 0)
      hdf5::fail("H5Fget_file_image", quoted);
    hdf5::seal_superblock(image);
    file.close("H5Fclose", quoted);
  }
  write_bytes(file_name, image, checkpoint != nullptr);
}

// Rows of a 1-D dataset (columns == 0) or of a rows x columns dataset.
hsize_t row_count(hid_t file, const std::string& path, hsize_t columns) {
  const Shape shape = hdf5::dataset_shape(file, path);
  const bool matches = columns == 0 ? shape.size() == 1 : shape.size() == 2 && shape[1] == columns;
  if (!matches) {
    throw InputError("dataset " + path + " is " + hdf5::shape_text(shape) + ", expected " +
                     (columns == 0 ? "a 1-D array" : "? x " + std::to_string(columns)));
  }
  return shape[0];
}

Provenance read_provenance(hid_t file) {
  const std::string group = "/provenance";
  Provenance provenance;
  provenance.software = hdf5::read_string_attribute(file, group, "software");
  provenance.version = hdf5::read_string_attribute(file, group, "version");
  provenance.git_commit = hdf5::read_string_attribute(file, group, "git_commit");
  provenance.command_line = hdf5::read_string_attribute(file, group, "command_line");
  provenance.problem = hdf5::read_string_attribute(file, group, "problem");
  provenance.created = hdf5::read_string_attribute(file, group, "created");
  provenance.seed = hdf5::read_attribute<std::uint64_t>(file, group, "seed");
  return provenance;
}

SceneInfo read_scene(hid_t file) {
  const std::string group = "/scene";
  SceneInfo scene;
  scene.name = hdf5::read_string_attribute(file, group, "name");
  scene.criterion = hdf5::read_string_attribute(file, group, "criterion");
  scene.dim = hdf5::read_attribute<int>(file, group, "dim");
  scene.spacing = hdf5::read_attribute<double>(file, group, "spacing");
  scene.exaggeration = hdf5::read_attribute<double>(file, group, "exaggeration");
  // Files written before the two models were named have no "model".
  if (hdf5::has_attribute(file, group, "model"))
    scene.model = hdf5::read_string_attribute(file, group, "model");
  if (scene.dim != 2 && scene.dim != 3)
    throw InputError("/scene dim is " + std::to_string(scene.dim) + ", not 2 or 3");
  if (!(scene.spacing > 0))
    throw InputError("/scene spacing is " + std::to_string(scene.spacing) +
                     " m, not a positive length");
  return scene;
}

std::vector<BreakEvent> read_events(hid_t file) {
  const Shape shape{row_count(file, "/events/lambda", 0)};
  const auto lambda = hdf5::read_dataset<double>(file, "/events/lambda", shape);
  const auto bond = hdf5::read_dataset<std::int64_t>(file, "/events/bond", shape);
  const auto failure_index = hdf5::read_dataset<double>(file, "/events/f", shape);
  const auto mode = hdf5::read_dataset<std::int8_t>(file, "/events/mode", shape);
  const auto cascade = hdf5::read_dataset<std::int64_t>(file, "/events/cascade", shape);
  std::vector<BreakEvent> events(shape[0]);
  for (std::size_t i = 0; i < events.size(); ++i) {
    if (mode[i] < 0 || mode[i] > static_cast<std::int8_t>(BreakMode::precut)) {
      throw Error("/events/mode[" + std::to_string(i) + "] is " + std::to_string(mode[i]) +
                  ": a break mode is 0 (tensile), 1 (shear) or 2 (pre-cut)");
    }
    events[i] = {lambda[i], bond[i], failure_index[i], static_cast<BreakMode>(mode[i]), cascade[i]};
  }
  return events;
}

std::vector<Snapshot> read_snapshots(hid_t file, hsize_t nodes, hsize_t bonds) {
  std::vector<Snapshot> snapshots(hdf5::link_count(file, "/snapshots"));
  for (std::size_t i = 0; i < snapshots.size(); ++i) {
    const std::string group = snapshot_group(i);
    if (!hdf5::exists(file, group)) {
      throw InputError("group " + group + " is missing (the groups in /snapshots must be " +
                       "named 0, 1, ... " + std::to_string(snapshots.size() - 1) + ")");
    }
    Snapshot& snapshot = snapshots[i];
    snapshot.lambda = hdf5::read_attribute<double>(file, group, "lambda");
    snapshot.displacement = hdf5::read_dataset<double>(file, group + "/displacement", {nodes, 3});
    snapshot.bond_intact = hdf5::read_dataset<std::uint8_t>(file, group + "/bond_intact", {bonds});
    snapshot.bond_failure_index = hdf5::read_dataset<double>(file, group + "/bond_f", {bonds});
    snapshot.node_stress = hdf5::read_dataset<double>(file, group + "/node_stress", {nodes, 6});
  }
  return snapshots;
}

RunSummary read_summary(hid_t file) {
  const std::string group = "/summary";
  RunSummary summary;
  summary.breaks = hdf5::read_attribute<std::int64_t>(file, group, "breaks");
  summary.solves = hdf5::read_attribute<std::int64_t>(file, group, "solves");
  summary.factorizations = hdf5::read_attribute<std::int64_t>(file, group, "factorizations");
  summary.factor_updates = hdf5::read_attribute<std::int64_t>(file, group, "factor_updates");
  // Counters added after the first result files: absent means zero.
  auto optional_count = [&](const char* name) -> std::int64_t {
    return hdf5::has_attribute(file, group, name)
               ? hdf5::read_attribute<std::int64_t>(file, group, name)
               : 0;
  };
  summary.contact_cycles = optional_count("contact_cycles");
  summary.relaxation_sweeps = optional_count("relaxation_sweeps");
  summary.relaxation_unconverged = optional_count("relaxation_unconverged");
  summary.floor_acceptances = optional_count("floor_acceptances");
  summary.final_lambda = hdf5::read_attribute<double>(file, group, "final_lambda");
  if (hdf5::has_attribute(file, group, "friction_work")) {
    summary.contact_slip = hdf5::read_attribute<double>(file, group, "contact_slip");
    summary.friction_work = hdf5::read_attribute<double>(file, group, "friction_work");
  }
  summary.wall_seconds = hdf5::read_attribute<double>(file, group, "wall_seconds");
  // Files written before runs were written as they went are complete.
  summary.complete = !hdf5::has_attribute(file, group, "complete") ||
                     hdf5::read_attribute<std::uint8_t>(file, group, "complete") != 0;
  for (const std::int64_t count :
       {summary.breaks, summary.solves, summary.factorizations, summary.factor_updates,
        summary.contact_cycles, summary.relaxation_sweeps, summary.relaxation_unconverged,
        summary.floor_acceptances})
    if (count < 0)
      throw InputError("/summary holds a negative count (" + std::to_string(count) +
                       "), which latfrac never writes");
  return summary;
}

// Files written before fragments were recorded have no /fragments: none then.
std::vector<FragmentEvent> read_fragments(hid_t file) {
  std::vector<FragmentEvent> fragments;
  if (!hdf5::exists(file, "/fragments/lambda")) return fragments;
  const Shape shape{row_count(file, "/fragments/lambda", 0)};
  const auto lambda = hdf5::read_dataset<double>(file, "/fragments/lambda", shape);
  const auto nodes = hdf5::read_dataset<std::int64_t>(file, "/fragments/nodes", shape);
  for (hsize_t i = 0; i < shape[0]; ++i) fragments.push_back({lambda[i], nodes[i]});
  return fragments;
}

RunResult read_contents(hid_t file) {
  RunResult result;
  result.provenance = read_provenance(file);
  result.scene = read_scene(file);
  const hsize_t nodes = row_count(file, "/lattice/positions", 3);
  const hsize_t bonds = row_count(file, "/lattice/bonds", 2);
  result.positions = hdf5::read_dataset<double>(file, "/lattice/positions", {nodes, 3});
  result.bonds = hdf5::read_dataset<std::int64_t>(file, "/lattice/bonds", {bonds, 2});
  result.bond_kind = hdf5::read_dataset<std::int8_t>(file, "/lattice/bond_kind", {bonds});
  result.events = read_events(file);
  result.fragments = read_fragments(file);
  result.snapshots = read_snapshots(file, nodes, bonds);
  result.summary = read_summary(file);
  if (hdf5::exists(file, "/friction/slip")) {
    result.contact_slip = hdf5::read_dataset<double>(file, "/friction/slip", {bonds});
    result.friction_work = hdf5::read_dataset<double>(file, "/friction/work", {bonds});
  }
  if (hdf5::exists(file, "/contact/normal"))
    result.contact_normal = hdf5::read_dataset<double>(file, "/contact/normal", {bonds, 3});
  return result;
}

}  // namespace

void write_result_file(const std::string& path, const RunResult& result,
                       const RunCheckpoint* checkpoint) {
  check_sizes(result);
  check_result_finite(result);
  hdf5::QuietErrors quiet;
  try {
    write_atomically(path,
                     [&](const std::string& partial) { write_hdf5(partial, result, checkpoint); });
  } catch (const Error& error) {
    throw Error("cannot write result file '" + path + "': " + error.what());
  }
}

namespace {

// Opens a latfrac result file for reading and calls read(file); InputError for a missing,
// non-HDF5 or non-latfrac file, or for a missing or misshapen object.
template <class Read>
auto read_from(const std::string& path, Read read) {
  hdf5::QuietErrors quiet;
  const std::string quoted = "'" + path + "'";
  std::error_code ignored;
  if (!std::filesystem::exists(path, ignored)) {
    throw InputError("result file " + quoted + " does not exist");
  }
  if (H5Fis_hdf5(path.c_str()) <= 0) {
    throw InputError(quoted + " is not a latfrac result file: it is not an HDF5 file");
  }
  try {
    hdf5::Handle file = hdf5::checked(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose,
                                      "H5Fopen", quoted);
    if (!hdf5::exists(file.get(), "/provenance")) {
      throw InputError(quoted + " is an HDF5 file but not a latfrac result file: " +
                       "it has no /provenance group");
    }
    try {
      return read(file.get());
    } catch (const InputError& error) {
      throw InputError("result file " + quoted + " is incomplete or damaged: " + error.what());
    }
  } catch (const Error& error) {
    // A library call that fails on a file latfrac wrote whole means the file was cut short
    // or damaged since: the user's input, as the checksums' failures are (exit 2).
    throw InputError("cannot read result file " + quoted +
                     " (damaged or cut short?): " + error.what());
  }
}

}  // namespace

RunResult read_result_file(const std::string& path) {
  RunResult result = read_from(path, read_contents);
  // latfrac writes no value that is not finite (check_result_finite), so one is damage:
  // analyze and render would print "inf m" and draw nothing.
  if (const auto bad = first_non_finite(result))
    throw InputError("'" + path + "' holds " + *bad +
                     ", which latfrac never writes: the file is damaged");
  // An event for a bond the lattice does not have: every reader refuses it, not only the
  // fault analysis (render drew the others and said nothing).
  for (const BreakEvent& event : result.events)
    if (event.bond < 0 || static_cast<std::size_t>(event.bond) >= result.bond_count())
      throw InputError("'" + path + "' has a break event for bond " + std::to_string(event.bond) +
                       " of " + std::to_string(result.bond_count()) + ": the file is damaged");
  return result;
}

RunCheckpoint read_checkpoint(const std::string& path) {
  const bool complete = read_from(path, [](hid_t file) { return read_summary(file).complete; });
  if (complete) {
    throw InputError("'" + path + "' is the result of a run that finished: there is nothing " +
                     "to resume");
  }
  return read_from(path, read_checkpoint_group);
}

}  // namespace latfrac
