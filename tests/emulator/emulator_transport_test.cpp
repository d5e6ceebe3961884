// EmulatorTransport: the emulator behind io::Transport on a ManualClock.
#include <gtest/gtest.h>

#include <array>

#include "runtime/emulator/emulator_transport.hpp"
#include "tests/emulator/emu_test_util.hpp"

namespace seqc::emu::test {
namespace {

Bytes read_all(EmulatorTransport& link, io::TimePoint deadline, io::ReadStatus& last) {
  Bytes out;
  std::array<std::uint8_t, 3> buf{};  // small on purpose: replies come in pieces
  while (true) {
    const io::ReadResult r = link.read(buf, deadline);
    last = r.status;
    if (r.status != io::ReadStatus::Data) return out;
    out.insert(out.end(), buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(r.count));
  }
}

TEST(EmulatorTransport, PacedRequestAndReplyInEmulatedTime) {
  XArmConfig config;
  config.baud = 9600;
  XArmEmulator emu(config);
  io::ManualClock clock(at_ms(1000));
  EmulatorTransport link(emu, clock);
  EXPECT_EQ(link.describe(), "emu:xarm");
  EXPECT_DOUBLE_EQ(link.seconds_per_byte(), 10.0 / 9600);
  const io::Duration byte{10'000'000'000LL / 9600};

  ASSERT_TRUE(link.write(hex("55 55 02 0f")).ok());
  EXPECT_EQ(clock.now(), at_ms(1000) + 4 * byte) << "writing 4 bytes takes 4 byte times";
  EXPECT_EQ(emu.received().at(0).at, at_ms(1000) + 4 * byte);

  io::ReadStatus last{};
  const Bytes reply = read_all(link, clock.now() + 100ms, last);
  EXPECT_EQ(hex_of(reply), "55 55 04 0f 4c 1d");
  EXPECT_EQ(last, io::ReadStatus::Timeout);
  EXPECT_EQ(clock.now(), at_ms(1100) + 4 * byte) << "the final read waited to its deadline";
}

TEST(EmulatorTransport, ReadReturnsAsSoonAsTheFirstByteIsDue) {
  XArmEmulator emu;  // unpaced, step 1 busy 60 ms
  io::ManualClock clock;
  EmulatorTransport link(emu, clock);
  ASSERT_TRUE(link.write(hex("55 55 04 05 01 00")).ok());  // step 1 with no counts: refused
  std::array<std::uint8_t, 16> buf{};
  auto r = link.read(buf, at_ms(500));
  ASSERT_EQ(r.status, io::ReadStatus::Data);
  EXPECT_EQ(hex_of(Bytes(buf.begin(), buf.begin() + 6)), "55 55 04 05 01 01");
  EXPECT_EQ(clock.now(), at_ms(0)) << "a refusal is immediate";

  ASSERT_TRUE(link.write(hex("55 55 05 05 01 00 01")).ok());
  r = link.read(buf, at_ms(500));
  ASSERT_EQ(r.status, io::ReadStatus::Data);
  EXPECT_EQ(clock.now(), at_ms(60)) << "the clock advanced to the acknowledgement";
}

TEST(EmulatorTransport, TimeoutWhenNothingComes) {
  XArmEmulator emu;
  io::ManualClock clock(at_ms(5));
  EmulatorTransport link(emu, clock);
  ASSERT_TRUE(link.write(hex("55 55 02 07 55 55 03 30 00")).ok());
  std::array<std::uint8_t, 16> buf{};
  auto r = link.read(buf, at_ms(10));
  ASSERT_EQ(r.status, io::ReadStatus::Data);  // GroupStopped
  EXPECT_EQ(r.count, 4u);
  r = link.read(buf, at_ms(250));
  EXPECT_EQ(r.status, io::ReadStatus::Timeout);
  EXPECT_EQ(clock.now(), at_ms(250));
  // A deadline already past: no waiting.
  r = link.read(buf, at_ms(100));
  EXPECT_EQ(r.status, io::ReadStatus::Timeout);
  EXPECT_EQ(clock.now(), at_ms(250));
}

TEST(EmulatorTransport, LateReplyBeyondDeadlineIsATimeoutThenArrives) {
  XArmConfig config;
  config.faults.late_ack = 1.0;
  config.faults.late_by = 400ms;
  XArmEmulator emu(config);
  io::ManualClock clock;
  EmulatorTransport link(emu, clock);
  ASSERT_TRUE(link.write(hex("55 55 02 0f")).ok());
  std::array<std::uint8_t, 16> buf{};
  EXPECT_EQ(link.read(buf, at_ms(300)).status, io::ReadStatus::Timeout);
  auto r = link.read(buf, at_ms(1000));
  ASSERT_EQ(r.status, io::ReadStatus::Data);
  EXPECT_EQ(clock.now(), at_ms(400));
  // discard_input drops what is due now.
  ASSERT_TRUE(link.write(hex("55 55 02 0f")).ok());
  clock.advance(500ms);
  link.discard_input();
  EXPECT_EQ(link.read(buf, at_ms(1000)).status, io::ReadStatus::Timeout);
}

TEST(EmulatorTransport, NotificationWakesAReader) {
  XArmEmulator emu;
  io::ManualClock clock;
  EmulatorTransport link(emu, clock);
  io::TimePoint t{0};
  ASSERT_TRUE(download(emu, 3, {lsc::GroupAction{250, {{1, 100}}}}, t));
  clock.sleep_until(t);
  ASSERT_TRUE(link.write(hex("55 55 05 06 03 01 00")).ok());
  io::ReadStatus last{};
  EXPECT_EQ(hex_of(read_all(link, t + 1s, last)), "55 55 05 06 03 01 00 55 55 05 08 03 01 00");
  EXPECT_EQ(last, io::ReadStatus::Timeout);
}

TEST(EmulatorTransport, HangUp) {
  XArmConfig config;
  config.faults.hangup_at = 2;
  XArmEmulator emu(config);
  io::ManualClock clock;
  EmulatorTransport link(emu, clock);
  ASSERT_TRUE(link.write(hex("55 55 02 0f")).ok());
  std::array<std::uint8_t, 16> buf{};
  EXPECT_EQ(link.read(buf, at_ms(100)).status, io::ReadStatus::Data);
  ASSERT_TRUE(link.write(hex("55 55 02 0f")).ok());
  const auto r = link.read(buf, at_ms(200));
  EXPECT_EQ(r.status, io::ReadStatus::HangUp);
  EXPECT_EQ(clock.now(), at_ms(0)) << "a hang-up is reported at once, not after the deadline";
  EXPECT_FALSE(link.write(hex("55 55 02 0f")).ok());
}

}  // namespace
}  // namespace seqc::emu::test
