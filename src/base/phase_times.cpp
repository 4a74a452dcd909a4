// The clock behind a run's time by part (phase_times.h).
#include "latfrac/base/phase_times.h"

#include <chrono>

namespace latfrac {

namespace {

double steady_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

const char* to_string(Phase phase) {
  switch (phase) {
    case Phase::other:
      return "the rest";
    case Phase::setup:
      return "setup";
    case Phase::solve:
      return "solves";
    case Phase::factor_update:
      return "factor updates";
    case Phase::refactorize:
      return "refactorizations";
    case Phase::node_stress:
      return "node stresses";
    case Phase::criterion:
      return "criterion";
    case Phase::residual:
      return "residual checks";
    case Phase::contacts:
      return "contacts";
    case Phase::output:
      return "output";
  }
  return "?";
}

PhaseClock::PhaseClock() : PhaseClock(steady_seconds) {}

PhaseClock::PhaseClock(Now now) : now_(std::move(now)), since_(now_()) {}

void PhaseClock::enter(Phase phase) {
  const double now = now_();
  seconds_[static_cast<int>(open_.empty() ? Phase::other : open_.back())] += now - since_;
  since_ = now;
  open_.push_back(phase);
}

void PhaseClock::leave() {
  if (open_.empty()) return;
  const double now = now_();
  seconds_[static_cast<int>(open_.back())] += now - since_;
  since_ = now;
  open_.pop_back();
}

std::array<double, phase_count> PhaseClock::seconds() const {
  std::array<double, phase_count> total = seconds_;
  total[static_cast<int>(open_.empty() ? Phase::other : open_.back())] += now_() - since_;
  return total;
}

void PhaseClock::reset() {
  seconds_.fill(0);
  open_.clear();
  since_ = now_();
}

PhaseClock& phase_clock() {
  thread_local PhaseClock clock;
  return clock;
}

}  // namespace latfrac
