// RAII ownership of HDF5 identifiers, and HDF5 failures turned into latfrac::Error messages.
#include "hdf5_handles.h"

#include <cstdint>
#include <cstring>
#include <utility>

#include "latfrac/base/error.h"

// HDF5's checksum of its metadata (Jenkins' lookup3), exported by libhdf5 since 1.8.7 but
// declared only in its private headers.
extern "C" std::uint32_t H5_checksum_metadata(const void* data, std::size_t len,
                                              std::uint32_t initval);

namespace latfrac::hdf5 {

Handle::Handle(Handle&& other) noexcept
    : id_(std::exchange(other.id_, H5I_INVALID_HID)), closer_(other.closer_) {}

Handle& Handle::operator=(Handle&& other) noexcept {
  if (this != &other) {
    release();
    id_ = std::exchange(other.id_, H5I_INVALID_HID);
    closer_ = other.closer_;
  }
  return *this;
}

void Handle::release() noexcept {
  if (id_ >= 0 && closer_ != nullptr) closer_(id_);
  id_ = H5I_INVALID_HID;
}

void Handle::close(const char* call, const std::string& object) {
  const hid_t id = std::exchange(id_, H5I_INVALID_HID);
  if (id >= 0 && closer_ != nullptr) check(closer_(id), call, object);
}

namespace {

// H5Ewalk2 visits the innermost error first when walking upward; that one says what
// actually went wrong (e.g. "errno = 2, error message = 'No such file or directory'").
herr_t keep_innermost(unsigned depth, const H5E_error2_t* error, void* message) {
  if (depth == 0 && error->desc != nullptr) *static_cast<std::string*>(message) = error->desc;
  return 0;
}

}  // namespace

void fail(const char* call, const std::string& object) {
  std::string detail;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, keep_innermost, &detail);
  std::string message = std::string("HDF5 ") + call + " failed for " + object;
  if (!detail.empty()) message += ": " + detail;
  throw Error(message);
}

QuietErrors::QuietErrors() {
  H5Eget_auto2(H5E_DEFAULT, &previous_function_, &previous_data_);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

QuietErrors::~QuietErrors() { H5Eset_auto2(H5E_DEFAULT, previous_function_, previous_data_); }

void seal_superblock(std::vector<char>& image) {
  // Version 2 and 3 superblocks: signature (8 bytes), version, size of offsets, size of
  // lengths, status flags, then four addresses and the checksum of everything before it.
  static constexpr char signature[] = "\x89HDF\r\n\x1a\n";
  if (image.size() < 12 || std::memcmp(image.data(), signature, 8) != 0) return;
  const auto version = static_cast<unsigned char>(image[8]);
  if (version < 2) return;
  const std::size_t end = 12 + 4 * static_cast<std::size_t>(static_cast<unsigned char>(image[9]));
  if (image.size() < end + 4) return;
  const std::uint32_t sum = H5_checksum_metadata(image.data(), end, 0);
  std::uint32_t stored = 0;
  for (int b = 3; b >= 0; --b)
    stored = (stored << 8) | static_cast<unsigned char>(image[end + static_cast<std::size_t>(b)]);
  if (stored == sum) return;
  for (std::size_t b = 0; b < 4; ++b) image[end + b] = static_cast<char>((sum >> (8 * b)) & 0xff);
}

}  // namespace latfrac::hdf5
