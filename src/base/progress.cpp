// The progress line of long runs.
#include "latfrac/base/progress.h"

#include <unistd.h>

#include <cstdio>

namespace latfrac {

ProgressLine::ProgressLine(bool enabled)
    : enabled_(enabled),
      terminal_(isatty(STDERR_FILENO)),
      start_(std::chrono::steady_clock::now()),
      last_(start_) {}

void ProgressLine::update(double lambda, std::int64_t breaks) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double since_last = std::chrono::duration<double>(now - last_).count();
  if (elapsed < 1.0 || since_last < (terminal_ ? 0.5 : 10.0)) return;
  last_ = now;
  std::fprintf(stderr, "%slambda %.6g   bonds broken %lld   elapsed %.1f s   %.1f breaks/s%s",
               terminal_ ? "\r" : "", lambda, static_cast<long long>(breaks), elapsed,
               breaks / elapsed, terminal_ ? "   " : "\n");
  std::fflush(stderr);
  printed_ = true;
}

void ProgressLine::finish() {
  if (enabled_ && printed_ && terminal_) std::fputc('\n', stderr);
}

}  // namespace latfrac
