// The Raspblock's in-process transport on a ManualClock, and `seqc emulate`'s servers: bad
// options end before a terminal is made, and a server told to stop reports its device, its
// settings and what it received.
#include <gtest/gtest.h>

#include <atomic>
#include <optional>
#include <string>
#include <vector>

#include "runtime/emulator/emulator_serve.hpp"
#include "runtime/emulator/raspblock_emulator.hpp"
#include "runtime/emulator/raspblock_transport.hpp"

namespace seqc::emu {
namespace {

using std::chrono::milliseconds;

// Remembers what a server reported while it ran.
class Events final : public ServeEvents {
 public:
  void serving(const std::string& path, const std::string& what,
               const std::string& after_path) override {
    paths.push_back(path);
    device = what;
    settings = after_path;
  }
  void hung_up(std::size_t, io::Duration) override { ++hang_ups; }
  void back(const std::string& path) override { paths.push_back(path); }
  std::ostream* log() override { return nullptr; }

  std::vector<std::string> paths;
  std::string device;
  std::string settings;
  int hang_ups = 0;
};

TEST(RaspblockTransport, WritesReachTheBoardAtTheTimeSinceOpening) {
  io::ManualClock clock(milliseconds(5000));
  RaspblockEmulator board;
  RaspblockTransport link(board, clock);
  clock.advance(milliseconds(250));
  // Servo 3 to 2000 us: ff fe 02 03 03 07 d0 df.
  const Bytes servo{0xff, 0xfe, 0x02, 0x03, 0x03, 0x07, 0xd0, 0xdf};
  ASSERT_TRUE(link.write(servo).ok());
  ASSERT_EQ(board.packets().size(), 1u);
  EXPECT_EQ(board.packets()[0].at, milliseconds(250));
  EXPECT_EQ(board.received_bytes(), servo);
  EXPECT_EQ(link.describe(), "emu:raspblock");
}

TEST(RaspblockTransport, AReadWaitsForItsDeadlineBecauseTheBoardNeverReplies) {
  io::ManualClock clock(milliseconds(100));
  RaspblockEmulator board;
  RaspblockTransport link(board, clock);
  std::uint8_t buffer[8];
  const io::ReadResult r = link.read(buffer, milliseconds(400));
  EXPECT_EQ(r.status, io::ReadStatus::Timeout);
  EXPECT_EQ(r.count, 0u);
  EXPECT_EQ(clock.now(), milliseconds(400));
}

TEST(EmulatorServe, BadOptionsEndBeforeAnyTerminalIsMade) {
  io::ManualClock clock;
  std::atomic<bool> stop{false};
  Events events;

  ServeOptions faults;
  faults.faults = "no-such-fault=1";
  const ServeResult xarm = serve_xarm(faults, clock, stop, events);
  EXPECT_EQ(xarm.status, ServeStatus::BadFaults);
  EXPECT_FALSE(xarm.detail.empty());
  EXPECT_EQ(xarm.device, "an xArm controller");

  ServeOptions positions;
  positions.positions = "1=";
  const ServeResult bad_positions = serve_xarm(positions, clock, stop, events);
  EXPECT_EQ(bad_positions.status, ServeStatus::BadPositions);
  EXPECT_FALSE(bad_positions.detail.empty());

  const ServeResult lsc6 = serve_lsc6(faults, clock, stop, events);
  EXPECT_EQ(lsc6.status, ServeStatus::BadFaults);
  EXPECT_EQ(lsc6.device, "an LSC-6 board");

  EXPECT_TRUE(events.paths.empty());
}

TEST(EmulatorServe, AServerToldToStopReportsItsDeviceAndWhatItReceived) {
  io::SteadyClock clock;
  const std::atomic<bool> stop{true};

  ServeOptions options;
  options.record = true;
  Events xarm_events;
  const ServeResult xarm = serve_xarm(options, clock, stop, xarm_events);
  EXPECT_EQ(xarm.status, ServeStatus::Stopped);
  ASSERT_EQ(xarm_events.paths.size(), 1u);
  EXPECT_EQ(xarm_events.device, "an xArm controller");
  EXPECT_EQ(xarm_events.settings, " (9600 baud, faults: none)");
  EXPECT_EQ(xarm.received, "0 frames, 0 bytes");
  EXPECT_EQ(xarm.record, "time_s,status,bytes,message\n");

  ServeOptions lsc6_options;
  lsc6_options.baud = 0;
  lsc6_options.faults = "no-run-reply";
  lsc6_options.dump_groups = true;
  Events lsc6_events;
  const ServeResult lsc6 = serve_lsc6(lsc6_options, clock, stop, lsc6_events);
  EXPECT_EQ(lsc6.status, ServeStatus::Stopped);
  EXPECT_EQ(lsc6_events.device, "an LSC-6 board");
  EXPECT_EQ(lsc6_events.settings, " (unpaced, no answer to Run)");
  EXPECT_EQ(lsc6.received, "0 frames, 0 bytes");
  EXPECT_TRUE(lsc6.record.empty());

  Events car_events;
  const ServeResult car = serve_raspblock(options, clock, stop, car_events);
  EXPECT_EQ(car.status, ServeStatus::Stopped);
  EXPECT_EQ(car_events.device, "a Raspblock board");
  EXPECT_EQ(car_events.settings, "; state changes follow");
  EXPECT_EQ(car.received, "0 packets, 0 rejected (0 bad checksums)");
  EXPECT_EQ(car.record, "time_s,field,previous,value\n");
}

}  // namespace
}  // namespace seqc::emu
