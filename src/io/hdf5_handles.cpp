// RAII ownership of HDF5 identifiers, and HDF5 failures turned into latfrac::Error messages.
#include "hdf5_handles.h"

#include <utility>

#include "latfrac/base/error.h"

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

}  // namespace latfrac::hdf5
