// The benchmarks' driver: each case in a child process, so that its peak memory is its own.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <exception>
#include <utility>
#include <vector>

namespace latfrac::bench {

// Runs run_case(dim, nodes) for every case, each in a forked child; a failure is printed
// and the next case runs.
template <typename RunCase>
void run_each_in_child(const std::vector<std::pair<int, long>>& cases, RunCase run_case) {
  for (const auto& [dim, nodes] : cases) {
    std::fflush(stdout);
    const pid_t child = fork();
    if (child == 0) {
      try {
        run_case(dim, nodes);
      } catch (const std::exception& e) {
        std::fprintf(stderr, "bench: %s\n", e.what());
        _exit(1);
      }
      _exit(0);
    }
    int status = 0;
    waitpid(child, &status, 0);
  }
}

}  // namespace latfrac::bench
