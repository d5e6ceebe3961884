// The clock is an interface passed in: the uploader, player and emulator runner never read the
// wall clock or sleep on their own, so tests drive them with ManualClock in microseconds.
#pragma once

#include <chrono>

namespace seqc::io {

// Monotonic time since an arbitrary epoch fixed for the clock's lifetime.
using Duration = std::chrono::nanoseconds;
using TimePoint = std::chrono::nanoseconds;

class Clock {
 public:
  virtual ~Clock() = default;
  virtual TimePoint now() const = 0;
  // Returns at or after `deadline` (immediately if it has passed).
  virtual void sleep_until(TimePoint deadline) = 0;
};

// CLOCK_MONOTONIC through std::chrono::steady_clock.
class SteadyClock final : public Clock {
 public:
  TimePoint now() const override;
  void sleep_until(TimePoint deadline) override;
};

// Emulated time: only moves when told to (or when something sleeps on it).
class ManualClock final : public Clock {
 public:
  explicit ManualClock(TimePoint start = TimePoint{0}) : now_(start) {}
  TimePoint now() const override { return now_; }
  void sleep_until(TimePoint deadline) override {
    if (deadline > now_) now_ = deadline;
  }
  void advance(Duration d) { now_ += d; }

 private:
  TimePoint now_;
};

}  // namespace seqc::io
