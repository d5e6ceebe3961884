// A scripted servo controller for the uploader's unit tests: an io::Transport on a ManualClock
// whose faults are chosen per request number (1-based, counting every framed request), so a
// test can say "lose the acknowledgement of the 40th frame" exactly. GroupDownload itself is
// the emulator's enforcing state machine (emu::GroupDownloader), so what is stored is what
// the product's emulator would store.
//
// Timing follows the emulator: a request is processed when its last byte arrives, keeps the
// controller busy (busy, or erase_busy for step 1); a request arriving while busy is dropped;
// the reply is ready when processing ends, plus `late` if scripted. Replies go out in order
// of readiness, so a late reply can come after a later one. GroupErase is answered with its
// empty reply (55 55 02 08) unless `erase_unanswered`. After a hang-up, reopen() brings the
// link back if `back_after` is set and that time has come by the deadline.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstring>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "runtime/emulator/group_store.hpp"
#include "runtime/io/clock.hpp"
#include "runtime/io/transport.hpp"
#include "protocol/lsc/lsc_messages.hpp"
#include "protocol/lsc/lsc_stream.hpp"

namespace seqc::upload::testing {

using namespace std::chrono_literals;

struct FakeScript {
  std::set<std::size_t> drop;                // request n is lost
  std::map<std::size_t, io::Duration> late;  // request n's reply comes this much later
  std::set<std::size_t> duplicate;           // request n's reply is sent twice
  // Request n's reply is followed back to back, in the same burst, by these bytes: a stale
  // reply the controller had queued behind it, which the host reads together with it.
  std::map<std::size_t, Bytes> trailing;
  io::Duration duplicate_gap{0};               // between a reply and its duplicate
  std::map<std::size_t, std::size_t> corrupt;  // request n's reply: byte k is xor-ed with ff
  std::set<std::size_t> refuse;                // request n is answered "<step> 01", no effect
  std::optional<std::size_t> hangup_at;        // the link closes when request n arrives
  std::optional<std::size_t> silent_after;     // no effect, no reply from request n+1 on
  // A power dip as request n arrives: the request is lost, a download in progress is forgotten
  // (its group stays empty) and the controller is deaf for boot_time.
  std::optional<std::size_t> reset_at;
  io::Duration boot_time = 300ms;
  bool erase_unanswered = false;           // GroupErase erases but sends no reply
  std::optional<io::Duration> back_after;  // after a hang-up the port can be opened again then
  io::Duration busy = 2ms;
  io::Duration erase_busy = 60ms;
  double seconds_per_byte = 0;  // write() and replies take this per byte on the clock
};

class FakeController final : public io::Transport {
 public:
  FakeController(io::ManualClock& clock, FakeScript script)
      : clock_(clock), script_(std::move(script)) {}

  Status write(ByteView bytes) override {
    if (hung_up_) return make_error("the fake controller hung up");
    clock_.advance(wire(bytes.size()));
    in_.feed(bytes);
    while (auto frame = in_.next()) handle(*frame);
    return Ok{};
  }

  io::ReadResult read(std::span<std::uint8_t> buffer, io::TimePoint deadline) override {
    if (hung_up_) return {io::ReadStatus::HangUp, 0, "the fake controller hung up"};
    if (out_.empty() || out_.front().at > deadline) {
      clock_.sleep_until(deadline);
      return {io::ReadStatus::Timeout, 0, ""};
    }
    clock_.sleep_until(out_.front().at);
    std::size_t n = 0;
    while (!out_.empty() && out_.front().at <= clock_.now() && n < buffer.size()) {
      Pending& p = out_.front();
      const std::size_t k = std::min(buffer.size() - n, p.bytes.size());
      std::memcpy(buffer.data() + n, p.bytes.data(), k);
      n += k;
      p.bytes.erase(p.bytes.begin(), p.bytes.begin() + static_cast<long>(k));
      if (p.bytes.empty()) out_.erase(out_.begin());
    }
    return {io::ReadStatus::Data, n, ""};
  }

  void discard_input() override {
    std::erase_if(out_, [&](const Pending& p) { return p.at <= clock_.now(); });
  }
  std::string describe() const override { return "fake controller"; }
  bool reopen(io::TimePoint deadline) override {
    if (!hung_up_ || !script_.back_after) return false;
    const io::TimePoint back = hung_up_at_ + *script_.back_after;
    if (back > deadline) {
      clock_.sleep_until(deadline);
      return false;
    }
    clock_.sleep_until(std::max(back, clock_.now()));
    hung_up_ = false;
    ++reopens_;
    return true;
  }
  double seconds_per_byte() const override { return script_.seconds_per_byte; }

  // What the controller holds in `group` (nullopt = empty).
  std::optional<std::vector<lsc::GroupAction>> stored(std::uint8_t group) const {
    return store_.group(group);
  }
  // Every framed request, in arrival order (also the lost and busy-dropped ones).
  const std::vector<lsc::Frame>& received() const { return received_; }
  std::size_t busy_dropped() const { return busy_dropped_; }
  std::size_t download_acks_sent() const { return acks_sent_; }
  bool hung_up() const { return hung_up_; }
  std::size_t reopens() const { return reopens_; }
  // Called with each request number as it arrives (e.g. to raise the interrupt flag).
  std::function<void(std::size_t)> on_request;

 private:
  struct Pending {
    io::TimePoint at;
    Bytes bytes;
  };

  io::Duration wire(std::size_t bytes) const {
    return io::Duration(
        static_cast<long long>(static_cast<double>(bytes) * script_.seconds_per_byte * 1e9));
  }

  void emit(const lsc::Frame& frame, io::TimePoint ready, std::size_t n) {
    Bytes bytes = lsc::encode_serial(frame).value();
    if (auto it = script_.corrupt.find(n); it != script_.corrupt.end()) {
      bytes[it->second % bytes.size()] ^= 0xff;
    }
    if (auto it = script_.late.find(n); it != script_.late.end()) ready += it->second;
    if (auto it = script_.trailing.find(n); it != script_.trailing.end()) {
      Bytes burst = bytes;
      burst.insert(burst.end(), it->second.begin(), it->second.end());
      queue(ready + wire(burst.size()), std::move(burst));
    } else {
      queue(ready + wire(bytes.size()), bytes);
    }
    if (script_.duplicate.count(n) != 0) {
      queue(ready + script_.duplicate_gap + wire(2 * bytes.size()), bytes);
    }
  }

  void queue(io::TimePoint at, Bytes bytes) {
    auto pos = std::upper_bound(out_.begin(), out_.end(), at,
                                [](io::TimePoint t, const Pending& p) { return t < p.at; });
    out_.insert(pos, Pending{at, std::move(bytes)});
  }

  void handle(const lsc::Frame& frame) {
    const std::size_t n = ++count_;
    received_.push_back(frame);
    if (on_request) on_request(n);
    if (script_.hangup_at && n == *script_.hangup_at) {
      hung_up_ = true;
      hung_up_at_ = clock_.now();
      out_.clear();
      return;
    }
    if (script_.silent_after && n > *script_.silent_after) return;
    if (script_.drop.count(n) != 0) return;
    const io::TimePoint now = clock_.now();
    if (script_.reset_at == n) {
      downloader_.abort();
      busy_until_ = now + script_.boot_time;
      return;
    }
    if (now < busy_until_) {
      ++busy_dropped_;
      return;
    }
    io::Duration busy = script_.busy;
    if (frame.cmd == static_cast<std::uint8_t>(lsc::Command::GroupDownload)) {
      lsc::GroupDownloadAck ack;
      if (script_.refuse.count(n) != 0) {
        ack.step = frame.data.empty() ? 0 : frame.data[0];
        ack.status = 1;
      } else {
        auto outcome = downloader_.handle(frame, store_);
        if (!outcome) return;
        ack = outcome->ack;
        if (outcome->work == emu::GroupDownloader::Work::FlashErase) busy = script_.erase_busy;
      }
      busy_until_ = now + busy;
      ++acks_sent_;
      emit(lsc::encode(lsc::Reply{ack}).value(), busy_until_, n);
      return;
    }
    busy_until_ = now + busy;
    auto request = lsc::decode_request(frame);
    if (!request) return;
    if (std::holds_alternative<lsc::GetBatteryVoltage>(*request)) {
      emit(lsc::encode(lsc::Reply{lsc::BatteryVoltage{7400}}).value(), busy_until_, n);
    } else if (std::holds_alternative<lsc::GroupStop>(*request)) {
      emit(lsc::encode(lsc::Reply{lsc::GroupStopped{}}).value(), busy_until_, n);
    } else if (const auto* erase = std::get_if<lsc::GroupErase>(&*request)) {
      store_.erase(erase->group);
      if (!script_.erase_unanswered) {
        emit(lsc::encode(lsc::Reply{lsc::GroupErased{}}).value(), busy_until_, n);
      }
    } else if (const auto* run = std::get_if<lsc::GroupRun>(&*request)) {
      if (store_.group(run->group)) {
        emit(lsc::encode(lsc::Reply{lsc::GroupStarted{run->group, run->times}}).value(),
             busy_until_, n);
      }
    }
  }

  io::ManualClock& clock_;
  FakeScript script_;
  lsc::FrameDecoder in_;
  std::vector<Pending> out_;  // by ready time; equal times keep their order
  emu::GroupStore store_;
  emu::GroupDownloader downloader_;
  std::vector<lsc::Frame> received_;
  std::size_t count_ = 0;
  std::size_t busy_dropped_ = 0;
  std::size_t acks_sent_ = 0;
  io::TimePoint busy_until_{0};
  bool hung_up_ = false;
  io::TimePoint hung_up_at_{0};
  std::size_t reopens_ = 0;
};

}  // namespace seqc::upload::testing
