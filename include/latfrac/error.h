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

}  // namespace latfrac
