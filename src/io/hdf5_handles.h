// RAII ownership of HDF5 identifiers, and HDF5 failures turned into latfrac::Error messages.
#pragma once

#include <hdf5.h>

#include <string>
#include <vector>

namespace latfrac::hdf5 {

// Owns one hid_t and releases it with its H5?close function when it goes out of scope.
class Handle final {
 public:
  using Closer = herr_t (*)(hid_t);

  Handle() = default;
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Handle(Handle&& other) noexcept;
  Handle& operator=(Handle&& other) noexcept;
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { release(); }

  hid_t get() const { return id_; }

  // Closes now and throws if closing fails: closing a file is what completes its writes.
  void close(const char* call, const std::string& object);

 private:
  void release() noexcept;

  hid_t id_ = H5I_INVALID_HID;
  Closer closer_ = nullptr;
};

// Throws latfrac::Error "HDF5 <call> failed for <object>: <HDF5's innermost message>".
// Must be called right after the failing call, before any other HDF5 call clears the stack.
[[noreturn]] void fail(const char* call, const std::string& object);

inline void check(herr_t status, const char* call, const std::string& object) {
  if (status < 0) fail(call, object);
}

inline Handle checked(hid_t id, Handle::Closer closer, const char* call,
                      const std::string& object) {
  if (id < 0) fail(call, object);
  return Handle(id, closer);
}

// Silences HDF5's automatic printing of error stacks for its lifetime (we report errors
// ourselves) and restores the previous setting afterwards.
class QuietErrors final {
 public:
  QuietErrors();
  ~QuietErrors();
  QuietErrors(const QuietErrors&) = delete;
  QuietErrors& operator=(const QuietErrors&) = delete;

 private:
  H5E_auto2_t previous_function_ = nullptr;
  void* previous_data_ = nullptr;
};

// An image of an open file from H5Fget_file_image, made whole. HDF5 1.10.8 clears the
// superblock's status flags in the image (version 2 and 3 superblocks: the "open for
// writing" mark) but leaves the checksum computed with them set, so the image would not
// open ("incorrect metadata checksum"). The checksum is computed again, with HDF5's own
// function, when it does not match; an image whose superblock has no checksum (version 0
// or 1) is left alone.
void seal_superblock(std::vector<char>& image);

}  // namespace latfrac::hdf5
