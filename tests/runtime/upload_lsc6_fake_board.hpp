// A scripted LSC-6 board for the LSC-6 uploader's rule tests: an io::Transport on a ManualClock
// whose faults are chosen per request number (1-based, counting every framed request, the
// opening Stop included), so a test can say "answer the 3rd frame 700 ms late" exactly.
//
// Answers follow docs/protocol/lsc-6.md: DownloadAction (CMD 19 hex) is answered 55 55 02 19
// and Run (CMD 06) 55 55 02 06, `busy` after the frame arrived; Stop (07) is not answered. The
// board stores nothing: these tests are about the path the uploader takes, and the emulator's
// tests about what is stored.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstring>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "runtime/io/clock.hpp"
#include "runtime/io/transport.hpp"
#include "protocol/lsc/lsc_stream.hpp"

namespace seqc::upload::testing {

struct Lsc6Script {
  std::set<std::size_t> drop;                // request n is lost
  std::map<std::size_t, io::Duration> late;  // request n's answer comes this much later
  std::set<std::size_t> duplicate;           // request n is answered twice, back to back
  std::optional<std::size_t> silent_after;   // nothing from request n+1 on is heard
  io::Duration busy = std::chrono::milliseconds(2);
};

class FakeLsc6Board final : public io::Transport {
 public:
  FakeLsc6Board(io::ManualClock& clock, Lsc6Script script)
      : clock_(clock), script_(std::move(script)) {}

  Status write(ByteView bytes) override {
    in_.feed(bytes);
    while (auto frame = in_.next()) handle(*frame);
    return Ok{};
  }

  io::ReadResult read(std::span<std::uint8_t> buffer, io::TimePoint deadline) override {
    if (out_.empty() || out_.front().at > deadline) {
      clock_.sleep_until(deadline);
      return {io::ReadStatus::Timeout, 0, ""};
    }
    clock_.sleep_until(out_.front().at);
    std::size_t n = 0;
    while (!out_.empty() && out_.front().at <= clock_.now() && n + 4 <= buffer.size()) {
      std::memcpy(buffer.data() + n, out_.front().bytes.data(), 4);
      n += 4;
      out_.erase(out_.begin());
    }
    return {io::ReadStatus::Data, n, ""};
  }

  void discard_input() override {
    std::erase_if(out_, [&](const Pending& p) { return p.at <= clock_.now(); });
  }
  std::string describe() const override { return "fake LSC-6"; }

  // The command byte of every framed request, in arrival order (lost ones too).
  const std::vector<std::uint8_t>& commands() const { return commands_; }
  // Called with each request number as it arrives (e.g. to raise the interrupt flag).
  std::function<void(std::size_t)> on_request;

 private:
  struct Pending {
    io::TimePoint at;
    Bytes bytes;
  };

  void answer(std::uint8_t cmd, io::TimePoint at) {
    auto pos = std::upper_bound(out_.begin(), out_.end(), at,
                                [](io::TimePoint t, const Pending& p) { return t < p.at; });
    out_.insert(pos, Pending{at, Bytes{0x55, 0x55, 0x02, cmd}});
  }

  void handle(const lsc::Frame& frame) {
    const std::size_t n = ++count_;
    commands_.push_back(frame.cmd);
    if (on_request) on_request(n);
    if (script_.silent_after && n > *script_.silent_after) return;
    if (script_.drop.count(n) != 0) return;
    if (frame.cmd != 0x19 && frame.cmd != 0x06) return;
    io::TimePoint at = clock_.now() + script_.busy;
    if (auto it = script_.late.find(n); it != script_.late.end()) at += it->second;
    answer(frame.cmd, at);
    if (script_.duplicate.count(n) != 0) answer(frame.cmd, at);
  }

  io::ManualClock& clock_;
  Lsc6Script script_;
  lsc::FrameDecoder in_;
  std::vector<Pending> out_;  // by time; equal times keep their order
  std::vector<std::uint8_t> commands_;
  std::size_t count_ = 0;
};

}  // namespace seqc::upload::testing
