// Checked SUNDIALS calls and an Eigen view of serial N_Vectors, shared by the KINSOL and
// CVODE drivers.
#pragma once

#include <nvector/nvector_serial.h>

#include <cstdlib>
#include <string>

#include "latfrac/base/error.h"
#include "latfrac/mechanics/model.h"

namespace latfrac::sundials {

// Throws Error naming the call when a SUNDIALS function returns a negative flag.
inline void check_flag(int flag, const char* call) {
  if (flag >= 0) return;
  throw Error(std::string(call) + " failed with flag " + std::to_string(flag));
}

template <typename T>
T* check_pointer(T* pointer, const char* call) {
  if (!pointer) throw Error(std::string(call) + " failed (returned NULL)");
  return pointer;
}

// The *GetReturnFlagName functions return a malloc'ed string.
inline std::string flag_name(char* name) {
  std::string text = name ? name : "unknown";
  std::free(name);
  return text;
}

inline Eigen::Map<Vector> as_vector(N_Vector v) {
  return {N_VGetArrayPointer(v), static_cast<Eigen::Index>(N_VGetLength(v))};
}

}  // namespace latfrac::sundials
