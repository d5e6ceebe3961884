// ControllerLink: request/response over a byte link, with notifications, garbage, hang-ups
// and interrupts, on a manual clock.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <deque>

#include "runtime/upload/controller_link.hpp"

namespace seqc::upload {
namespace {

using namespace std::chrono_literals;

// Bytes scheduled to arrive at given times; records what was written.
class ScriptedTransport final : public io::Transport {
 public:
  explicit ScriptedTransport(io::ManualClock& clock) : clock_(clock) {}
  void arrive(io::TimePoint at, Bytes bytes) { incoming_.push_back({at, std::move(bytes)}); }
  void hang_up_at(io::TimePoint at) { hangup_ = at; }

  Status write(ByteView bytes) override {
    written.insert(written.end(), bytes.begin(), bytes.end());
    return Ok{};
  }
  io::ReadResult read(std::span<std::uint8_t> buffer, io::TimePoint deadline) override {
    ++reads;
    if (!incoming_.empty() && incoming_.front().first <= deadline) {
      clock_.sleep_until(incoming_.front().first);
      Bytes b = std::move(incoming_.front().second);
      incoming_.pop_front();
      std::copy(b.begin(), b.end(), buffer.begin());
      return {io::ReadStatus::Data, b.size(), ""};
    }
    if (hangup_ && *hangup_ <= deadline) {
      clock_.sleep_until(*hangup_);
      return {io::ReadStatus::HangUp, 0, "gone"};
    }
    clock_.sleep_until(deadline);
    return {io::ReadStatus::Timeout, 0, ""};
  }
  void discard_input() override { incoming_.clear(); }
  std::string describe() const override { return "scripted"; }

  Bytes written;
  int reads = 0;

 private:
  io::ManualClock& clock_;
  std::deque<std::pair<io::TimePoint, Bytes>> incoming_;
  std::optional<io::TimePoint> hangup_;
};

class Seen final : public LinkObserver {
 public:
  void on_notification(const lsc::Reply& r) override { notes.push_back(lsc::describe(r)); }
  void on_unexpected(const lsc::Reply& r) override { unexpected.push_back(lsc::describe(r)); }
  void on_unparsed(const lsc::Frame&, const std::string& why) override { unparsed.push_back(why); }
  std::vector<std::string> notes, unexpected, unparsed;
};

Verdict take_battery(const lsc::Reply& r) {
  return std::holds_alternative<lsc::BatteryVoltage>(r) ? Verdict::Take : Verdict::Skip;
}

TEST(ControllerLink, SendWritesTheSerialFrame) {
  io::ManualClock clock;
  ScriptedTransport t(clock);
  ControllerLink link(t, clock);
  ASSERT_TRUE(link.send(lsc::GetBatteryVoltage{}).ok());
  EXPECT_EQ(t.written, (Bytes{0x55, 0x55, 0x02, 0x0f}));
  EXPECT_EQ(link.stats().bytes_sent, 4u);
}

TEST(ControllerLink, SkipsNotificationsAndGarbageThenTakesTheReply) {
  io::ManualClock clock;
  ScriptedTransport t(clock);
  // garbage, GroupFinished (55 55 05 08 00 01 00), stray 55, then the reply split in two reads
  t.arrive(1ms, {0x13, 0x37, 0x55, 0x55, 0x05, 0x08, 0x00, 0x01, 0x00, 0x55});
  t.arrive(2ms, {0x55, 0x55, 0x04});
  t.arrive(3ms, {0x0f, 0x4c, 0x1d});
  ControllerLink link(t, clock);
  Seen seen;
  link.set_observer(&seen);
  WaitResult w = link.wait_for(take_battery, 1s);
  ASSERT_EQ(w.status, WaitStatus::Matched);
  EXPECT_EQ(std::get<lsc::BatteryVoltage>(w.reply).millivolts, 7500);
  EXPECT_EQ(clock.now(), 3ms);
  ASSERT_EQ(seen.notes.size(), 1u);
  EXPECT_EQ(link.stats().garbage_bytes, 3u);
}

TEST(ControllerLink, UnknownFramesAreReportedAndSkipped) {
  io::ManualClock clock;
  ScriptedTransport t(clock);
  t.arrive(1ms, {0x55, 0x55, 0x02, 0x7e, 0x55, 0x55, 0x04, 0x05, 0x04, 0x00});
  ControllerLink link(t, clock);
  Seen seen;
  link.set_observer(&seen);
  WaitResult w = link.wait_for(take_battery, 10ms);
  EXPECT_EQ(w.status, WaitStatus::Timeout);
  EXPECT_EQ(seen.unparsed.size(), 1u);
  EXPECT_EQ(seen.unexpected.size(), 1u);  // the ack nobody asked for
  EXPECT_EQ(clock.now(), 10ms);
}

TEST(ControllerLink, HangUpIsNotATimeout) {
  io::ManualClock clock;
  ScriptedTransport t(clock);
  t.hang_up_at(40ms);
  ControllerLink link(t, clock);
  WaitResult w = link.wait_for(take_battery, 1s);
  EXPECT_EQ(w.status, WaitStatus::HangUp);
  EXPECT_EQ(clock.now(), 40ms);
}

TEST(ControllerLink, WaitsInSlicesAndStopsOnInterrupt) {
  io::ManualClock clock;
  ScriptedTransport t(clock);
  std::atomic<bool> flag{false};
  ControllerLink link(t, clock, &flag);
  WaitResult w = link.wait_for(take_battery, 1s);
  EXPECT_EQ(w.status, WaitStatus::Timeout);
  EXPECT_EQ(t.reads, 10);  // 100 ms slices
  flag = true;
  w = link.wait_for(take_battery, clock.now() + 10s);
  EXPECT_EQ(w.status, WaitStatus::Interrupted);
  EXPECT_EQ(clock.now(), 1s);
}

TEST(ControllerLink, DrainHandsOverWhatHasArrivedWithoutWaiting) {
  io::ManualClock clock;
  ScriptedTransport t(clock);
  t.arrive(0ms, {0x55, 0x55, 0x04, 0x05, 0x04, 0x00, 0x55, 0x55, 0x02, 0x07});
  t.arrive(5ms, {0x55, 0x55, 0x04, 0x05, 0x04, 0x00});
  ControllerLink link(t, clock);
  Seen seen;
  link.set_observer(&seen);
  int acks = 0;
  EXPECT_EQ(link.drain([&](const lsc::Reply& r) {
    if (std::holds_alternative<lsc::GroupDownloadAck>(r)) ++acks;
  }),
            WaitStatus::Timeout);
  EXPECT_EQ(acks, 1);
  EXPECT_EQ(seen.notes.size(), 1u);  // GroupStopped went to the observer
  EXPECT_EQ(clock.now(), 0ms);
}

}  // namespace
}  // namespace seqc::upload
