#pragma once
// Wall time of consecutive steps, for the step times the stages report.
// Not tested: a stopwatch; its figures only reach timing reports.
#include <chrono>

namespace isocurv {

/// The clock step times are measured with.
using StepClock = std::chrono::steady_clock;

/// Milliseconds since `since`, which then moves to now (so consecutive calls time consecutive
/// steps). Thread-safe as long as each thread has its own time point.
inline double lap(StepClock::time_point& since) {
  const StepClock::time_point now = StepClock::now();
  const double ms = std::chrono::duration<double, std::milli>(now - since).count();
  since = now;
  return ms;
}

}  // namespace isocurv
