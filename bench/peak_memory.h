// This process's peak resident memory, MiB (getrusage; kB on Linux).
#pragma once

#include <sys/resource.h>

inline double peak_mib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}
