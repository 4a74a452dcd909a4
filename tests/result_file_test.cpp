// Tests of the HDF5 result file: exact round trip, atomic writing, and clear read errors.
#include "latfrac/io/result_file.h"

#include <hdf5.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "latfrac/base/error.h"
#include "sample_result.h"

namespace latfrac {
namespace {

using testing::sample_result;
using testing::ScratchDirectory;

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!same_bits(a[i], b[i])) return false;
  }
  return true;
}

void require_equal(const RunResult& read, const RunResult& written) {
  const Provenance& p = read.provenance;
  const Provenance& q = written.provenance;
  CHECK(p.software == q.software);
  CHECK(p.version == q.version);
  CHECK(p.git_commit == q.git_commit);
  CHECK(p.command_line == q.command_line);
  CHECK(p.problem == q.problem);
  CHECK(p.created == q.created);
  CHECK(p.seed == q.seed);
  CHECK(read.scene.name == written.scene.name);
  CHECK(read.scene.dim == written.scene.dim);
  CHECK(same_bits(read.scene.spacing, written.scene.spacing));
  CHECK(read.scene.criterion == written.scene.criterion);
  CHECK(same_bits(read.scene.exaggeration, written.scene.exaggeration));
  CHECK(read.scene.model == written.scene.model);
  CHECK(same_bits(read.positions, written.positions));
  CHECK(read.bonds == written.bonds);
  CHECK(read.bond_kind == written.bond_kind);
  REQUIRE(read.events.size() == written.events.size());
  for (std::size_t i = 0; i < read.events.size(); ++i) {
    CHECK(same_bits(read.events[i].lambda, written.events[i].lambda));
    CHECK(read.events[i].bond == written.events[i].bond);
    CHECK(same_bits(read.events[i].failure_index, written.events[i].failure_index));
    CHECK(read.events[i].mode == written.events[i].mode);
    CHECK(read.events[i].cascade == written.events[i].cascade);
  }
  REQUIRE(read.snapshots.size() == written.snapshots.size());
  for (std::size_t i = 0; i < read.snapshots.size(); ++i) {
    const Snapshot& s = read.snapshots[i];
    const Snapshot& t = written.snapshots[i];
    CHECK(same_bits(s.lambda, t.lambda));
    CHECK(same_bits(s.displacement, t.displacement));
    CHECK(s.bond_intact == t.bond_intact);
    CHECK(same_bits(s.bond_failure_index, t.bond_failure_index));
    CHECK(same_bits(s.node_stress, t.node_stress));
  }
  CHECK(read.summary.breaks == written.summary.breaks);
  CHECK(same_bits(read.summary.final_lambda, written.summary.final_lambda));
  CHECK(same_bits(read.summary.wall_seconds, written.summary.wall_seconds));
  CHECK(read.summary.solves == written.summary.solves);
  CHECK(read.summary.factorizations == written.summary.factorizations);
  CHECK(read.summary.factor_updates == written.summary.factor_updates);
  CHECK(read.summary.floor_acceptances == written.summary.floor_acceptances);
  CHECK(same_bits(read.contact_normal, written.contact_normal));
}

// The message of the Exception that call throws; fails the test if it throws nothing.
template <class Exception, class Call>
std::string thrown_message(Call call) {
  try {
    call();
  } catch (const Exception& error) {
    return error.what();
  }
  FAIL("no exception was thrown");
  return {};
}

// Runs edit on the HDF5 file at path, opened for writing.
template <class Edit>
void edit_hdf5(const std::string& path, Edit edit) {
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  REQUIRE(file >= 0);
  edit(file);
  REQUIRE(H5Fclose(file) >= 0);
}

// Deletes the dataset at path and creates one of that type and shape in its place (its
// values unwritten).
void replace_dataset(hid_t file, const char* path, hid_t type, const std::vector<hsize_t>& shape) {
  REQUIRE(H5Ldelete(file, path, H5P_DEFAULT) >= 0);
  const hid_t space = H5Screate_simple(static_cast<int>(shape.size()), shape.data(), nullptr);
  const hid_t dataset = H5Dcreate2(file, path, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  REQUIRE(dataset >= 0);
  H5Dclose(dataset);
  H5Sclose(space);
}

// Finds the bytes of `value` in the file (they must occur once) and flips their lowest bit.
void flip_bit_of(const std::string& path, const void* value, std::size_t size) {
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const std::string pattern(static_cast<const char*>(value), size);
  const std::size_t at = bytes.find(pattern);
  REQUIRE(at != std::string::npos);
  REQUIRE(bytes.find(pattern, at + 1) == std::string::npos);
  bytes[at] = static_cast<char>(bytes[at] ^ 1);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << bytes;
}

}  // namespace

TEST_CASE("a result file reads back exactly what was written", "[io]") {
  ScratchDirectory scratch;
  const std::string path = scratch.file("graben.h5");
  RunResult written = sample_result();

  SECTION("with events and snapshots") {}
  SECTION("with contacts along cracks: each bond's contact normal") {
    written.contact_normal.clear();
    for (std::size_t b = 0; b < written.bond_count(); ++b) {
      const double angle = 0.3 + 0.7 * static_cast<double>(b);
      written.contact_normal.insert(written.contact_normal.end(),
                                    {std::cos(angle), 0.0, std::sin(angle)});
    }
  }
  SECTION("with no events and no snapshots") {
    written.events.clear();
    written.snapshots.clear();
  }
  SECTION("with no bonds") {
    written.bonds.clear();
    written.bond_kind.clear();
    written.events.clear();  // an event names a bond: without bonds, none
    for (Snapshot& snapshot : written.snapshots) {
      snapshot.bond_intact.clear();
      snapshot.bond_failure_index.clear();
    }
  }
  SECTION("with empty strings") {
    written.provenance = Provenance{};
    written.scene.criterion.clear();
    // A file written before the two models were named: no "model" attribute.
    written.scene.model.clear();
  }

  write_result_file(path, written);
  require_equal(read_result_file(path), written);
}

TEST_CASE("writing a result file replaces an existing one", "[io]") {
  ScratchDirectory scratch;
  const std::string path = scratch.file("graben.h5");
  write_result_file(path, sample_result());
  RunResult second = sample_result();
  second.snapshots.pop_back();
  second.summary.breaks = 99;
  write_result_file(path, second);
  require_equal(read_result_file(path), second);
}

TEST_CASE("a result file is written atomically", "[io]") {
  ScratchDirectory scratch;

  SECTION("a successful write leaves no partial file") {
    const std::string path = scratch.file("graben.h5");
    write_result_file(path, sample_result());
    CHECK(std::filesystem::exists(path));
    CHECK_FALSE(std::filesystem::exists(path + ".partial"));
  }
  SECTION("a write into a missing directory names the file and the reason, leaves nothing") {
    // The file is built in memory and written by latfrac itself (result_file.cpp): the
    // message names the file it could not create and the system's reason.
    const std::string path = scratch.file("no/such/directory/graben.h5");
    CHECK_THAT(thrown_message<Error>([&] { write_result_file(path, sample_result()); }),
               Catch::Matchers::Contains("cannot create '" + path + ".partial'") &&
                   Catch::Matchers::Contains("No such file or directory"));
    CHECK_FALSE(std::filesystem::exists(path));
    CHECK_FALSE(std::filesystem::exists(path + ".partial"));
  }
  SECTION("a failed rename removes the partial file and leaves the target alone") {
    const std::string path = scratch.file("occupied");
    std::filesystem::create_directories(path + "/inside");
    CHECK_THROWS_AS(write_result_file(path, sample_result()), Error);
    CHECK(std::filesystem::is_directory(path + "/inside"));
    CHECK_FALSE(std::filesystem::exists(path + ".partial"));
  }
  SECTION("an inconsistent RunResult is refused before anything is created") {
    const std::string path = scratch.file("graben.h5");
    RunResult result = sample_result();
    result.snapshots[1].node_stress.pop_back();
    CHECK_THAT(thrown_message<Error>([&] { write_result_file(path, result); }),
               Catch::Matchers::Contains("snapshot 1 node_stress"));
    CHECK(std::filesystem::is_empty(scratch.file("")));
  }
  SECTION("a NaN or an infinity anywhere is refused before anything is created") {
    const std::string path = scratch.file("graben.h5");
    const double bad = GENERATE(std::nan(""), std::numeric_limits<double>::infinity());
    auto refused = [&](auto&& spoil, const std::string& where) {
      RunResult result = sample_result();
      spoil(result);
      CHECK_THAT(thrown_message<Error>([&] { write_result_file(path, result); }),
                 Catch::Matchers::Contains(where) && Catch::Matchers::Contains("bug"));
      CHECK(std::filesystem::is_empty(scratch.file("")));
    };
    refused([&](RunResult& r) { r.snapshots[1].displacement[7] = bad; },
            "snapshot 1 displacement (entry 7)");
    refused([&](RunResult& r) { r.snapshots[0].node_stress[29] = bad; }, "snapshot 0 node_stress");
    refused([&](RunResult& r) { r.snapshots[0].bond_failure_index[2] = bad; }, "snapshot 0 bond_f");
    refused([&](RunResult& r) { r.events[2].lambda = bad; }, "events (event 2)");
    refused([&](RunResult& r) { r.positions[4] = bad; }, "lattice/positions");
  }
}

TEST_CASE("reading something that is not a complete latfrac result says why", "[io]") {
  ScratchDirectory scratch;
  const std::string path = scratch.file("graben.h5");
  using Catch::Matchers::Contains;

  SECTION("a missing file") {
    CHECK_THAT(thrown_message<InputError>([&] { read_result_file(path); }),
               Contains("does not exist"));
  }
  SECTION("a text file") {
    std::ofstream(path) << "name = \"graben\"\n";
    CHECK_THAT(thrown_message<InputError>([&] { read_result_file(path); }),
               Contains("not an HDF5 file"));
  }
  SECTION("an empty HDF5 file") {
    const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    REQUIRE(file >= 0);
    REQUIRE(H5Fclose(file) >= 0);
    CHECK_THAT(thrown_message<InputError>([&] { read_result_file(path); }),
               Contains("not a latfrac result") && Contains("/provenance"));
  }
  SECTION("a result without one of its datasets") {
    write_result_file(path, sample_result());
    edit_hdf5(path, [](hid_t file) { REQUIRE(H5Ldelete(file, "/events/f", H5P_DEFAULT) >= 0); });
    CHECK_THAT(thrown_message<InputError>([&] { read_result_file(path); }),
               Contains("/events/f is missing"));
  }
  SECTION("a result without one of its attributes") {
    write_result_file(path, sample_result());
    edit_hdf5(path, [](hid_t file) {
      REQUIRE(H5Adelete_by_name(file, "/summary", "solves", H5P_DEFAULT) >= 0);
    });
    CHECK_THAT(thrown_message<InputError>([&] { read_result_file(path); }),
               Contains("attribute 'solves' of /summary is missing"));
  }
  SECTION("a result with a dataset of the wrong shape") {
    write_result_file(path, sample_result());
    edit_hdf5(path, [](hid_t file) {
      replace_dataset(file, "/snapshots/1/node_stress", H5T_IEEE_F64LE, {5, 3});
    });
    CHECK_THAT(thrown_message<InputError>([&] { read_result_file(path); }),
               Contains("/snapshots/1/node_stress is 5 x 3, expected 5 x 6"));
  }
  SECTION("a result whose snapshots are not numbered 0, 1, ...") {
    write_result_file(path, sample_result());
    edit_hdf5(path, [](hid_t file) {
      REQUIRE(H5Lmove(file, "/snapshots/1", file, "/snapshots/7", H5P_DEFAULT, H5P_DEFAULT) >= 0);
    });
    CHECK_THAT(thrown_message<InputError>([&] { read_result_file(path); }),
               Contains("/snapshots/1 is missing"));
  }
  SECTION("a result with a flipped bit in a dataset's values (its checksum fails)") {
    // A value no other array holds, found in the file's bytes and its lowest mantissa bit
    // flipped: the number stays finite and plausible, so only the checksum can tell.
    RunResult result = sample_result();
    const double marker = 1234.5678901234567;
    result.snapshots[1].displacement[4] = marker;
    write_result_file(path, result);
    flip_bit_of(path, &marker, sizeof marker);
    CHECK_THAT(thrown_message<InputError>([&] { read_result_file(path); }),
               Contains("/snapshots/1/displacement") && Contains("damaged"));
  }
  SECTION("a result with a flipped bit in an attribute (its object header's checksum fails)") {
    // The attribute lives in its group's header, which the 1.10 format checksums; in the
    // format before it, the flipped count read back as another count, silently.
    RunResult result = sample_result();
    const std::int64_t marker = 104729104729;
    result.summary.solves = marker;
    write_result_file(path, result);
    flip_bit_of(path, &marker, sizeof marker);
    CHECK_THAT(thrown_message<InputError>([&] { read_result_file(path); }), Contains("damaged"));
  }
  SECTION("a result cut short") {
    write_result_file(path, sample_result());
    std::filesystem::resize_file(path, std::filesystem::file_size(path) / 2);
    CHECK_THAT(thrown_message<InputError>([&] { read_result_file(path); }),
               Contains("damaged or cut short"));
  }
  SECTION("a result whose numbers are stored wider than latfrac writes") {
    // HDF5 would convert 16-byte integers; a damaged width (524289 bytes) made it run off
    // its buffers, so a width latfrac never writes is refused before reading.
    write_result_file(path, sample_result());
    edit_hdf5(path, [](hid_t file) {
      const hid_t wide = H5Tcopy(H5T_STD_I64LE);
      REQUIRE(H5Tset_size(wide, 16) >= 0);
      replace_dataset(file, "/events/bond", wide, {3});
      H5Tclose(wide);
    });
    CHECK_THAT(thrown_message<InputError>([&] { read_result_file(path); }),
               Contains("/events/bond") && Contains("16 bytes"));
  }
  SECTION("a result with a break event for a bond the lattice does not have") {
    const RunResult result = sample_result();
    write_result_file(path, result);
    edit_hdf5(path, [&](hid_t file) {
      const hid_t dataset = H5Dopen2(file, "/events/bond", H5P_DEFAULT);
      REQUIRE(dataset >= 0);
      std::vector<std::int64_t> bonds(result.events.size(), 0);
      bonds.back() = static_cast<std::int64_t>(result.bond_count());
      REQUIRE(H5Dwrite(dataset, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, bonds.data()) >=
              0);
      H5Dclose(dataset);
    });
    CHECK_THAT(thrown_message<InputError>([&] { read_result_file(path); }),
               Contains("break event for bond " + std::to_string(result.bond_count())));
  }
}

}  // namespace latfrac
