// When to compile after a change: `delay` after the last change, so a burst of keystrokes
// costs one compile; a change while one is pending moves it later (supersedes it). Pure state
// with times passed in, so tests drive it with made-up times; the server's worker thread
// waits on it with the steady clock.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>

namespace seqc::lsp {

class Debounce {
 public:
  using Time = std::chrono::nanoseconds;
  explicit Debounce(Time delay) : delay_(delay) {}

  // A change at `now`: the compile is due `delay` later, whatever was due before.
  void touch(Time now) {
    due_ = now + delay_;
    ++generation_;
  }
  // When the pending compile is due, or nullopt when none is pending.
  std::optional<Time> due() const { return due_; }
  // Whether a compile is due at `now`; if so it is taken (no longer pending).
  bool take(Time now) {
    if (!due_ || now < *due_) return false;
    due_.reset();
    return true;
  }
  // Counts the changes: a compile started at one generation is stale once it has moved on.
  std::uint64_t generation() const { return generation_; }

 private:
  Time delay_;
  std::optional<Time> due_;
  std::uint64_t generation_ = 0;
};

}  // namespace seqc::lsp
