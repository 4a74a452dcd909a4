// Clean stops: SIGINT and SIGTERM set a flag that a run reads between events.
//
// The handler does no work: the first signal only records itself; the run notices it at
// its next check (fracture/run_control.h), writes a checkpoint and returns. A second
// signal restores the default action and raises it again, so the process stops at once;
// what was last written (renamed into place whole) stays readable (docs/restart.md).
#pragma once

#include <exception>

namespace latfrac {

// Thrown from inside one long solve (the relaxation's sweeps) when a stop was requested:
// the run cannot save a checkpoint in the middle of an event, so the result file keeps
// the last one written, and `latfrac run` says so and exits 3 as a clean stop does. (A
// relaxation solve at nu = 1/4 once ran for more than ten minutes inside one break's
// contact settling, and a single SIGTERM went unanswered.)
class StopWithinEvent : public std::exception {
 public:
  const char* what() const noexcept override {
    return "stopped on request inside an event (a solve that had not finished)";
  }
};

// Installs the handler for SIGINT and SIGTERM, and ignores SIGXFSZ so that a write past
// a file-size limit fails with EFBIG (a message, exit 1) instead of killing the process.
void install_stop_handlers();
// True once SIGINT or SIGTERM arrived (or request_stop() was called).
bool stop_requested();
// The signal that asked for the stop (0: none, or request_stop()).
int stop_signal();
// Asks for a stop as a signal would (tests, embedding programs).
void request_stop();
// Forgets a stop request (tests).
void clear_stop_request();

}  // namespace latfrac
