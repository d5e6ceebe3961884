// The dry run's device: records each write as one frame, answers from the acknowledge function,
// and otherwise lets its manual clock run to the read's deadline.
#include <gtest/gtest.h>

#include <array>
#include <chrono>

#include "runtime/boards/recording_transport.hpp"
#include "tests/boards/board_test_util.hpp"

namespace seqc::boards {
namespace {

using test_support::silent;

using std::chrono::milliseconds;

Bytes echo_length(ByteView request) { return Bytes{static_cast<std::uint8_t>(request.size())}; }
TEST(AcknowledgingTransport, RecordsEachWriteAndQueuesItsAnswer) {
  io::ManualClock clock;
  AcknowledgingTransport device(clock, echo_length);
  ASSERT_TRUE(device.write(Bytes{0x55, 0x55, 0x02, 0x0f}));
  ASSERT_TRUE(device.write(Bytes{0x01, 0x02}));
  ASSERT_EQ(device.writes().size(), 2u);
  EXPECT_EQ(device.writes()[0], (Bytes{0x55, 0x55, 0x02, 0x0f}));
  EXPECT_EQ(device.writes()[1], (Bytes{0x01, 0x02}));

  std::array<std::uint8_t, 1> one{};
  io::ReadResult r = device.read(one, clock.now() + milliseconds(10));
  EXPECT_EQ(r.status, io::ReadStatus::Data);
  EXPECT_EQ(r.count, 1u);
  EXPECT_EQ(one[0], 4);
  std::array<std::uint8_t, 8> more{};
  r = device.read(more, clock.now() + milliseconds(10));
  EXPECT_EQ(r.count, 1u);
  EXPECT_EQ(more[0], 2);
  EXPECT_EQ(clock.now(), io::TimePoint{});  // answers are there at once
}

TEST(AcknowledgingTransport, NothingQueuedTimesOutAtTheDeadline) {
  io::ManualClock clock;
  AcknowledgingTransport device(clock, silent);
  ASSERT_TRUE(device.write(Bytes{0x55, 0x55, 0x02, 0x07}));
  std::array<std::uint8_t, 8> buffer{};
  const io::ReadResult r = device.read(buffer, io::TimePoint{} + milliseconds(250));
  EXPECT_EQ(r.status, io::ReadStatus::Timeout);
  EXPECT_EQ(clock.now(), io::TimePoint{} + milliseconds(250));
}

TEST(AcknowledgingTransport, DiscardDropsQueuedAnswersAndIsUnpaced) {
  io::ManualClock clock;
  AcknowledgingTransport device(clock, echo_length);
  ASSERT_TRUE(device.write(Bytes{1, 2, 3}));
  device.discard_input();
  std::array<std::uint8_t, 8> buffer{};
  EXPECT_EQ(device.read(buffer, clock.now()).status, io::ReadStatus::Timeout);
  EXPECT_EQ(device.seconds_per_byte(), 0.0);
  EXPECT_EQ(device.describe(), "dry run");
}

}  // namespace
}  // namespace seqc::boards
