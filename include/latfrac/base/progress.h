// A progress line on stderr for long runs: lambda, bonds broken, elapsed time, rate.
//
// Silent for the first second (short runs print nothing), then at most twice a second;
// on a terminal it rewrites one line, elsewhere (a log, CI) it prints a line every 10 s.
#pragma once

#include <chrono>
#include <cstdint>

namespace latfrac {

class ProgressLine {
 public:
  explicit ProgressLine(bool enabled);
  void update(double lambda, std::int64_t breaks);
  void finish();

 private:
  bool enabled_;
  bool terminal_;
  bool printed_ = false;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace latfrac
