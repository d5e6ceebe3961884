#include "runtime/io/clock.hpp"

#include <thread>

namespace seqc::io {

TimePoint SteadyClock::now() const {
  return std::chrono::duration_cast<TimePoint>(std::chrono::steady_clock::now().time_since_epoch());
}

void SteadyClock::sleep_until(TimePoint deadline) {
  std::this_thread::sleep_until(std::chrono::steady_clock::time_point(
      std::chrono::duration_cast<std::chrono::steady_clock::duration>(deadline)));
}

}  // namespace seqc::io
