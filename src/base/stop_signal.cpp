// The stop flag and its signal handler.
#include "latfrac/base/stop_signal.h"

#include <csignal>

namespace latfrac {
namespace {

volatile std::sig_atomic_t requested = 0;  // 0, -1 (request_stop) or the signal number

// Async-signal-safe: a store, or signal() and raise() for the second signal.
extern "C" void on_stop_signal(int signal_number) {
  if (requested != 0) {
    std::signal(signal_number, SIG_DFL);
    std::raise(signal_number);
    return;
  }
  requested = signal_number;
}

}  // namespace

void install_stop_handlers() {
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  std::signal(SIGXFSZ, SIG_IGN);
}

bool stop_requested() { return requested != 0; }
int stop_signal() { return requested > 0 ? static_cast<int>(requested) : 0; }
void request_stop() { requested = -1; }
void clear_stop_request() { requested = 0; }

}  // namespace latfrac
