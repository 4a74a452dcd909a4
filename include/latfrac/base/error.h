// Error types: InputError for anything the user can fix (exit status 2), Error otherwise.
#pragma once

#include <stdexcept>
#include <string>

namespace latfrac {

// Bad input: a problem file, a command-line option, a parameter out of range.
// The message is for the user: it names the file, line and key where they apply.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A failure that is not the user's input: a library call, an I/O failure, a solver
// breakdown. The message names the call that failed.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The stiffness matrix has no stiffness along some motion: a factorization met a zero or
// negligible pivot. `unknown` is the free degree of freedom where it showed (-1 unknown),
// so that a caller can hold it and try again (docs/robustness.md).
class SingularStiffness : public Error {
 public:
  SingularStiffness(const std::string& message, long long unknown)
      : Error(message), unknown_(unknown) {}
  long long unknown() const { return unknown_; }

 private:
  long long unknown_;
};

}  // namespace latfrac
