// The host's steady clock, remembering the first time it was read. A pseudo-terminal server
// (emu::PtyServer) reads its clock once when it starts serving and stamps what it receives
// relative to that, so a test that waits for first() to be set knows the server is serving and
// can date what the board received on the host's clock.
#pragma once

#include <atomic>

#include "runtime/io/clock.hpp"

namespace seqc::testing {

class FirstReadClock final : public io::Clock {
 public:
  io::TimePoint now() const override {
    const io::TimePoint t = real_.now();
    io::TimePoint unset{-1};
    first_.compare_exchange_strong(unset, t);
    return t;
  }
  void sleep_until(io::TimePoint deadline) override { real_.sleep_until(deadline); }
  // io::TimePoint{-1} until the clock is first read.
  io::TimePoint first() const { return first_.load(); }

 private:
  io::SteadyClock real_;
  mutable std::atomic<io::TimePoint> first_{io::TimePoint{-1}};
};

}  // namespace seqc::testing
