// Clean stops: SIGINT and SIGTERM set a flag that a run reads between events.
//
// The handler does no work: the first signal only records itself; the run notices it at
// its next check (fracture/run_control.h), writes a checkpoint and returns. A second
// signal restores the default action and raises it again, so the process stops at once;
// what was last written (renamed into place whole) stays readable (docs/restart.md).
#pragma once

namespace latfrac {

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
