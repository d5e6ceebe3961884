// The follower on a scripted ShowClock, in emulated time: a servo controller's group stored on
// Open, started on Start and stopped on Stop; the car's stream anchored on Start and re-anchored
// by a Sync that jumps 10 s; --offset's sign; the offsets' summary.
#include <gtest/gtest.h>

#include <chrono>
#include <deque>

#include "compiler/compile.hpp"
#include "runtime/boards/board.hpp"
#include "runtime/emulator/emulator_transport.hpp"
#include "runtime/emulator/raspblock_emulator.hpp"
#include "runtime/emulator/raspblock_transport.hpp"
#include "runtime/emulator/xarm_emulator.hpp"
#include "runtime/follow/follower.hpp"
#include "runtime/io/disk.hpp"

namespace seqc::follow {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

compiler::CompileOutput compile_example(const char* name) {
  io::DiskFileReader files;
  return compiler::compile_file(std::string(SEQC_SOURCE_DIR) + "/examples/" + name, files);
}

// Events at their instants; once they are all told, the source has ended.
class ScriptedClock final : public ShowClock {
 public:
  explicit ScriptedClock(io::ManualClock& clock) : clock_(clock) {}
  void add(ShowClockKind kind, io::TimePoint at, double dance_ms) {
    events_.push_back({kind, dance_ms, at, "script"});
  }
  std::optional<ShowClockEvent> next(io::TimePoint deadline) override {
    if (!events_.empty() && events_.front().at <= deadline) {
      clock_.sleep_until(events_.front().at);
      ShowClockEvent e = events_.front();
      events_.pop_front();
      return e;
    }
    clock_.sleep_until(deadline);
    return std::nullopt;
  }
  bool ended() const override { return events_.empty(); }

 private:
  io::ManualClock& clock_;
  std::deque<ShowClockEvent> events_;
};

// The frames the controller took of one command (55 55 LEN CMD ...), with their arrival.
std::vector<std::pair<Bytes, io::TimePoint>> frames_of(const emu::XArmEmulator& c,
                                                       std::uint8_t cmd) {
  std::vector<std::pair<Bytes, io::TimePoint>> out;
  for (const emu::ReceivedFrame& f : c.received()) {
    if (f.raw.size() >= 4 && f.raw[3] == cmd) out.emplace_back(f.raw, f.at);
  }
  return out;
}

TEST(Follower, OpenStoresTheGroupStartRunsItStopStopsIt) {
  const compiler::CompileOutput walk = compile_example("../tests/data/walk-joints.yaml");
  ASSERT_TRUE(walk.program.has_value());
  const boards::Board& board = boards::board_for(walk);
  io::ManualClock clock;
  emu::XArmEmulator controller{emu::XArmConfig{}};
  emu::EmulatorTransport transport(controller, clock);
  const boards::Line line{transport, clock};
  ScriptedClock script(clock);
  script.add(ShowClockKind::Open, seconds(1), 0);
  script.add(ShowClockKind::Start, seconds(60), 0);
  script.add(ShowClockKind::Sync, seconds(61), 1000);
  script.add(ShowClockKind::Stop, seconds(62), 0);
  Follower follower(board, walk, line, clock, {});
  const FollowReport r = follower.run(script);
  EXPECT_EQ(r.end, FollowEnd::Stopped) << r.error;
  EXPECT_EQ(r.groups, 1u);
  // Stored on Open: group 0 holds every action of the dance (GroupDownload is CMD 0x05).
  const auto stored = controller.stored_group(0);
  ASSERT_TRUE(stored.has_value());
  EXPECT_EQ(stored->size(), walk.servo_program()->keyframes.size());
  EXPECT_FALSE(frames_of(controller, 0x05).empty());
  for (const auto& [bytes, at] : frames_of(controller, 0x05)) EXPECT_LT(at, seconds(60));
  // Started on Start: GroupRun of group 0, once, at 60 s, written with a GroupStop before it.
  const auto runs = frames_of(controller, 0x06);
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_EQ(to_hex(runs[0].first), "55 55 05 06 00 01 00");
  EXPECT_NEAR(std::chrono::duration<double>(runs[0].second).count(), 60.0, 0.0002);
  // Stopped on Stop: a GroupStop at 62 s, after the one written with the run (and the upload's
  // own before its download).
  const auto stops = frames_of(controller, 0x07);
  ASSERT_GE(stops.size(), 2u);
  const auto& with_run = stops[stops.size() - 2];
  const auto& last = stops.back();
  EXPECT_LE(with_run.second, runs[0].second);
  EXPECT_GE(with_run.second, seconds(60) - milliseconds(12));
  EXPECT_EQ(to_hex(last.first), "55 55 02 07");
  EXPECT_GE(last.second, seconds(62));
  EXPECT_LT(last.second, seconds(62) + milliseconds(10));
  EXPECT_TRUE(r.stop_sent);
  ASSERT_EQ(r.offsets_ms.size(), 1u);
  EXPECT_NEAR(r.offsets_ms[0], 0.0, 1e-6);
}

TEST(Follower, APositiveOffsetRunsTheRobotLater) {
  const compiler::CompileOutput walk = compile_example("../tests/data/walk-joints.yaml");
  const boards::Board& board = boards::board_for(walk);
  io::ManualClock clock;
  emu::XArmEmulator controller{emu::XArmConfig{}};
  emu::EmulatorTransport transport(controller, clock);
  const boards::Line line{transport, clock};
  ScriptedClock script(clock);
  script.add(ShowClockKind::Open, seconds(1), 0);
  script.add(ShowClockKind::Start, seconds(60), 0);
  script.add(ShowClockKind::Stop, seconds(62), 0);
  FollowerOptions options;
  options.offset = milliseconds(250);
  Follower follower(board, walk, line, clock, options);
  (void)follower.run(script);
  const auto runs = frames_of(controller, 0x06);
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_NEAR(std::chrono::duration<double>(runs[0].second).count(), 60.25, 0.0002);
}

TEST(Follower, ACarSyncThatJumpsTenSecondsReanchorsTheStreamAtOnce) {
  const compiler::CompileOutput car = compile_example("car-dance.yaml");
  ASSERT_TRUE(car.program.has_value());
  const boards::Board& board = boards::board_for(car);
  io::ManualClock clock;
  emu::RaspblockEmulator emulator;
  emu::RaspblockTransport transport(emulator, clock);
  const boards::Line line{transport, clock};
  ScriptedClock script(clock);
  script.add(ShowClockKind::Start, seconds(1), 0);
  script.add(ShowClockKind::Sync, seconds(2), 1000);           // on time
  script.add(ShowClockKind::Sync, milliseconds(3010), 12010);  // the master jumped 10 s ahead
  script.add(ShowClockKind::Stop, milliseconds(3600), 0);
  Follower follower(board, car, line, clock, {});
  const FollowReport r = follower.run(script);
  EXPECT_EQ(r.end, FollowEnd::Stopped) << r.error;
  ASSERT_EQ(r.offsets_ms.size(), 2u);
  EXPECT_NEAR(r.offsets_ms[0], 0.0, 1e-6);
  EXPECT_NEAR(r.offsets_ms[1], -10000.0, 1e-6);  // the robot 10 s behind
  EXPECT_EQ(r.corrections, 1u);

  const auto& got = emulator.packets();
  // The packets up to dance time 2.0 s (frame at 2000 ms: horizontal 1539), each arriving at
  // 1 s + its time (the in-process board takes no wire time); then at 3.01 s what the car should
  // be doing at 12.01 s: the last gimbal frame before it (6480 ms) and the rocker of 12000 ms;
  // then the rocker of 12500 ms at 3.5 s; then the stop at 3.6 s.
  std::size_t jump = 0;
  while (jump < got.size() && got[jump].at < milliseconds(3010)) ++jump;
  ASSERT_GE(jump, 2u);
  ASSERT_EQ(got.size(), jump + 4);
  const auto hex = [&](std::size_t i) { return to_hex(*raspblock::encode(got[i].packet)); };
  const auto at_ms = [&](std::size_t i) {
    return std::chrono::duration<double, std::milli>(got[i].at).count();
  };
  EXPECT_EQ(hex(0), "ff fe 01 09 00 3c 0a 28 00 14 1e 00 0a b4");  // the PID settings at 0
  EXPECT_NEAR(at_ms(0), 1000, 0.001);
  EXPECT_EQ(hex(jump - 1), "ff fe 02 04 06 03 05 78 8c");  // 2000 ms
  EXPECT_NEAR(at_ms(jump - 1), 3000, 0.001);
  EXPECT_EQ(hex(jump), "ff fe 02 04 05 dc 07 6c 5a");  // 6480 ms, caught up
  EXPECT_NEAR(at_ms(jump), 3010, 0.001);
  EXPECT_EQ(hex(jump + 1), "ff fe 03 08 01 00 0a 00 0a 00 00 01 21");  // 12000 ms
  EXPECT_NEAR(at_ms(jump + 1), 3010, 0.001);
  EXPECT_EQ(hex(jump + 2), "ff fe 03 08 01 00 0a 00 0a 00 00 07 27");  // 12500 ms
  EXPECT_NEAR(at_ms(jump + 2), 3500, 0.001);
  EXPECT_EQ(hex(jump + 3), "ff fe 03 08 01 00 00 00 00 00 00 01 0d");  // the stop
  EXPECT_NEAR(at_ms(jump + 3), 3600, 0.001);
  EXPECT_TRUE(r.stop_sent);
}

TEST(Follower, TheSourceEndingStopsTheCar) {
  const compiler::CompileOutput car = compile_example("car-dance.yaml");
  const boards::Board& board = boards::board_for(car);
  io::ManualClock clock;
  emu::RaspblockEmulator emulator;
  emu::RaspblockTransport transport(emulator, clock);
  const boards::Line line{transport, clock};
  ScriptedClock script(clock);
  script.add(ShowClockKind::Start, seconds(1), 0);
  Follower follower(board, car, line, clock, {});
  const FollowReport r = follower.run(script);
  EXPECT_EQ(r.end, FollowEnd::SourceEnded);
  EXPECT_TRUE(r.stop_sent);
  ASSERT_FALSE(emulator.packets().empty());
  EXPECT_EQ(to_hex(*raspblock::encode(emulator.packets().back().packet)),
            "ff fe 03 08 01 00 00 00 00 00 00 01 0d");
}

TEST(Follower, ASecondStartOfTheSameRunMovesNothing) {
  const compiler::CompileOutput walk = compile_example("../tests/data/walk-joints.yaml");
  const boards::Board& board = boards::board_for(walk);
  io::ManualClock clock;
  emu::XArmEmulator controller{emu::XArmConfig{}};
  emu::EmulatorTransport transport(controller, clock);
  const boards::Line line{transport, clock};
  ScriptedClock script(clock);
  script.add(ShowClockKind::Start, seconds(60), 0);
  script.add(ShowClockKind::Start, milliseconds(60005), 0);  // the entry's media, 5 ms later
  script.add(ShowClockKind::Stop, seconds(62), 0);
  Follower follower(board, walk, line, clock, {});
  const FollowReport r = follower.run(script);
  EXPECT_EQ(r.end, FollowEnd::Stopped) << r.error;
  EXPECT_EQ(r.starts, 2u);
  EXPECT_EQ(frames_of(controller, 0x06).size(), 1u);
}

TEST(Follower, AShowsPerformersFollowOneClockAndAStopStopsThemAll) {
  const compiler::CompileOutput walk = compile_example("../tests/data/walk-joints.yaml");
  const compiler::CompileOutput car = compile_example("car-dance.yaml");
  io::ManualClock clock;
  emu::XArmEmulator controller{emu::XArmConfig{}};
  emu::EmulatorTransport arm_transport(controller, clock);
  const boards::Line arm_line{arm_transport, clock};
  emu::RaspblockEmulator emulator;
  emu::RaspblockTransport car_transport(emulator, clock);
  const boards::Line car_line{car_transport, clock};
  ScriptedClock script(clock);
  script.add(ShowClockKind::Open, seconds(1), 0);
  script.add(ShowClockKind::Start, seconds(60), 0);
  script.add(ShowClockKind::Stop, seconds(61), 0);
  Follower arm(boards::board_for(walk), walk, arm_line, clock, {});
  Follower car_follower(boards::board_for(car), car, car_line, clock, {});
  std::vector<Follower*> all = {&arm, &car_follower};
  const FollowAll end = follow_all(all, script, clock, nullptr, milliseconds(20), true);
  EXPECT_EQ(end.end, FollowEnd::Stopped);
  EXPECT_FALSE(end.failed.has_value());
  EXPECT_EQ(frames_of(controller, 0x06).size(), 1u);
  EXPECT_EQ(to_hex(frames_of(controller, 0x07).back().first), "55 55 02 07");
  EXPECT_GE(frames_of(controller, 0x07).back().second, seconds(61));
  ASSERT_FALSE(emulator.packets().empty());
  EXPECT_EQ(emulator.packets().front().at, seconds(60));
  EXPECT_EQ(emulator.packets().back().at, seconds(61));  // the car's stop
  EXPECT_EQ(to_hex(*raspblock::encode(emulator.packets().back().packet)),
            "ff fe 03 08 01 00 00 00 00 00 00 01 0d");
  EXPECT_TRUE(arm.report().stop_sent);
  EXPECT_TRUE(car_follower.report().stop_sent);
}

TEST(Follower, WithoutOnceItStaysForTheNextStartWithTheGroupStillStored) {
  const compiler::CompileOutput walk = compile_example("../tests/data/walk-joints.yaml");
  const boards::Board& board = boards::board_for(walk);
  io::ManualClock clock;
  emu::XArmEmulator controller{emu::XArmConfig{}};
  emu::EmulatorTransport transport(controller, clock);
  const boards::Line line{transport, clock};
  ScriptedClock script(clock);
  script.add(ShowClockKind::Open, seconds(1), 0);
  script.add(ShowClockKind::Start, seconds(60), 0);
  script.add(ShowClockKind::Stop, seconds(70), 0);
  script.add(ShowClockKind::Open, seconds(80), 0);
  script.add(ShowClockKind::Start, seconds(80), 0);
  script.add(ShowClockKind::Stop, seconds(90), 0);
  FollowerOptions options;
  options.once = false;
  Follower follower(board, walk, line, clock, options);
  const FollowReport r = follower.run(script);
  EXPECT_EQ(r.end, FollowEnd::SourceEnded);
  EXPECT_EQ(r.starts, 2u);
  EXPECT_EQ(r.stops, 2u);
  const auto runs = frames_of(controller, 0x06);
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_NEAR(std::chrono::duration<double>(runs[1].second).count(), 80.0, 0.0002);
  // Stored once: no GroupDownload after the first run began.
  for (const auto& [bytes, at] : frames_of(controller, 0x05)) EXPECT_LT(at, seconds(60));
  const auto stops = frames_of(controller, 0x07);
  ASSERT_GE(stops.size(), 4u);  // with each run, and on each Stop
  EXPECT_GE(stops.back().second, seconds(90));
}

TEST(Follower, AStoredGroupFarOffRestartsAtTheNextPieceOnTheMastersTime) {
  // sway.yaml: 120 bpm in 4/4, so with --resync 1 a piece starts every bar, 2 s apart.
  const compiler::CompileOutput sway = compile_example("sway.yaml");
  ASSERT_TRUE(sway.program.has_value());
  const boards::Board& board = boards::board_for(sway);
  io::ManualClock clock;
  emu::XArmEmulator controller{emu::XArmConfig{}};
  emu::EmulatorTransport transport(controller, clock);
  const boards::Line line{transport, clock};
  ScriptedClock script(clock);
  script.add(ShowClockKind::Open, seconds(1), 0);
  script.add(ShowClockKind::Start, seconds(60), 0);
  script.add(ShowClockKind::Sync, milliseconds(60500), 500);   // on time
  script.add(ShowClockKind::Sync, milliseconds(61000), 3000);  // the master jumped 2 s ahead
  script.add(ShowClockKind::Stop, seconds(65), 0);             // before group 4's bar (66 s)
  FollowerOptions options;
  options.resync_bars = 1;
  Follower follower(board, sway, line, clock, options);
  const FollowReport r = follower.run(script);
  EXPECT_EQ(r.end, FollowEnd::Stopped) << r.error;
  EXPECT_EQ(r.groups, 5u);  // bars at 0, 2, 4, 6 and 8 s
  ASSERT_EQ(follower.schedule().size(), 5u);
  EXPECT_EQ(follower.schedule()[2].at, seconds(4));
  EXPECT_EQ(r.corrections, 1u);
  // Group 0 at 60 s; group 1 (the bar at 2 s, 1 s gone by the jump) is never started; group 2
  // (the bar at 4 s) at 62 s, when the master's clock reaches it; group 3 at 64 s.
  const auto runs = frames_of(controller, 0x06);
  ASSERT_EQ(runs.size(), 3u);
  EXPECT_EQ(runs[0].first[4], 0);
  EXPECT_EQ(runs[1].first[4], 2);
  EXPECT_EQ(runs[2].first[4], 3);
  EXPECT_NEAR(std::chrono::duration<double>(runs[1].second).count(), 62.0, 0.0002);
  EXPECT_NEAR(std::chrono::duration<double>(runs[2].second).count(), 64.0, 0.0002);
}

TEST(Follower, OffsetsAreSummarisedByTheirSize) {
  const OffsetSummary s = summarize_offsets({-4, 1, 2, -3, 10});
  EXPECT_EQ(s.median, 3);
  EXPECT_EQ(s.p99, 10);
  EXPECT_EQ(s.max, 10);
}

}  // namespace
}  // namespace seqc::follow
