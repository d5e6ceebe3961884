// The robot that follows the studio's playhead, in process on manual clocks: an xArm emulator at
// 9600 baud (emu:xarm through the boards' port opening) records every move it receives, the car's
// emulator every packet. Expected positions and times are worked out by hand in each test from
// its small choreography.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <variant>
#include <vector>

#include "protocol/lsc/lsc_frame.hpp"
#include "protocol/lsc/lsc_messages.hpp"
#include "runtime/boards/ports.hpp"
#include "runtime/emulator/xarm_emulator.hpp"
#include "runtime/studio/robot_follower.hpp"
#include "tests/compiler/lang_test_util.hpp"

namespace seqc::studio {
namespace {

using namespace std::chrono_literals;
using compiler::testing::compile_text;
using compiler::testing::diagnostics_of;

struct Move {
  io::TimePoint at{0};  // when its last byte reached the controller
  std::uint16_t time_ms = 0;
  std::map<std::uint8_t, std::uint16_t> targets;
};

// An xArm emulator at 9600 baud behind emu:xarm, sharing the follower's clock.
struct Xarm {
  io::ManualClock clock;
  emu::XArmEmulator controller{[] {
    emu::XArmConfig c;
    c.baud = 9600;
    return c;
  }()};
  boards::OpenedPort port;
  std::unique_ptr<RobotFollower> follower;

  // `base_at`: the base is moved there (by hand, as it were) before the follower starts.
  explicit Xarm(const compiler::CompileOutput& dance,
                std::optional<std::uint16_t> base_at = std::nullopt) {
    if (base_at) {
      lsc::MultiServoMove move{20, {{6, *base_at}}};
      controller.receive(lsc::encode_serial(lsc::Request{move}).value(), clock.now());
      clock.advance(100ms);
      controller.advance_to(clock.now());
    }
    const boards::Board& board = *boards::find_board("xarm");
    boards::OpenResult opened =
        boards::open_port({"emu:xarm", &board}, clock, {&controller, nullptr, &clock, nullptr});
    EXPECT_TRUE(opened.port.has_value());
    port = std::move(*opened.port);
    follower = std::make_unique<RobotFollower>(board, *port.transport, clock);
    follower->set_program(dance);
  }

  // Every MultiServoMove received, in order.
  std::vector<Move> moves() const {
    std::vector<Move> out;
    for (const emu::ReceivedFrame& f : controller.received()) {
      if (!f.frame) continue;
      const auto request = lsc::decode_request(*f.frame);
      if (!request) continue;
      const auto* m = std::get_if<lsc::MultiServoMove>(&*request);
      if (m == nullptr) continue;
      Move move{f.at, m->time_ms, {}};
      for (const auto& e : m->servos) move.targets[e.id] = e.position.value_or(0);
      out.push_back(move);
    }
    return out;
  }

  // Runs the follower's schedule until `until` on the clock.
  void run_until(io::TimePoint until) {
    for (int guard = 0; guard < 100000; ++guard) {
      const std::optional<io::TimePoint> next = follower->service();
      if (!next || *next > until) break;
      clock.sleep_until(std::max(*next, clock.now()));
    }
    clock.sleep_until(until);
  }
};

constexpr std::uint8_t kBase = 6;
constexpr std::uint8_t kClaw = 1;

// base 500 (its home) -> 700 in a straight line over 1000 ms, at most 400 units a second.
const char* const kSlowBase =
    "robot:\n"
    "  profile: xarm\n"
    "  servos:\n"
    "    base: {max_speed: 400/s}\n"
    "sequence:\n"
    "  - move: {base: 700}\n"
    "    time: 1000ms\n"
    "    ease: linear\n"
    "  - wait: 1000ms\n";

TEST(RobotFollower, AScrubMovesToTheDancesPositionNoFasterThanMaxSpeed) {
  const compiler::CompileOutput dance = compile_text(kSlowBase);
  ASSERT_NE(dance.servo_program(), nullptr) << diagnostics_of(dance);
  Xarm xarm(dance);
  // 250 ms into the straight line: 500 + 200 x 0.25 = 550, from home 500: 50 / 400 = 125 ms.
  const FollowerState s = xarm.follower->report({250, PlayheadMode::Scrubbed, false});
  std::vector<Move> moves = xarm.moves();
  ASSERT_EQ(moves.size(), 1u);
  EXPECT_EQ(moves[0].targets, (std::map<std::uint8_t, std::uint16_t>{{kBase, 550}}));
  EXPECT_EQ(moves[0].time_ms, 125);
  EXPECT_TRUE(s.slewing);
  // Back on the playhead once the move has arrived (10 bytes, 10.42 ms at 9600 baud) and ended.
  EXPECT_NEAR(s.slew_until_ms, 250 + 10.42 + 125, 0.01);
  // Once it is there, a scrub to 750 ms (650) is 100 units away: 250 ms.
  xarm.run_until(xarm.clock.now() + 500ms);
  EXPECT_FALSE(xarm.follower->report({250, PlayheadMode::Paused, false}).slewing);
  xarm.follower->report({750, PlayheadMode::Scrubbed, false});
  moves = xarm.moves();
  ASSERT_EQ(moves.size(), 2u);
  EXPECT_EQ(moves[1].targets, (std::map<std::uint8_t, std::uint16_t>{{kBase, 650}}));
  EXPECT_EQ(moves[1].time_ms, 250);
  // A scrub to where the robot already is sends nothing.
  xarm.run_until(xarm.clock.now() + 500ms);
  EXPECT_FALSE(xarm.follower->report({750, PlayheadMode::Scrubbed, false}).slewing);
  EXPECT_EQ(xarm.moves().size(), 2u);
}

// A scrub while the servo is still moving away from the new target: the move is timed from where
// the servo will be when it arrives (a 10-byte move is 10.42 ms at 9600 baud), 15 ms either side
// for the line's jitter, whichever is farthest, never from where it is when it is written.
TEST(RobotFollower, AScrubDuringASlewIsTimedFromWhereTheServoIsWhenTheMoveArrives) {
  const compiler::CompileOutput dance = compile_text(kSlowBase);
  ASSERT_NE(dance.servo_program(), nullptr) << diagnostics_of(dance);
  Xarm xarm(dance);
  xarm.follower->report({750, PlayheadMode::Scrubbed, false});  // to 650
  xarm.run_until(xarm.clock.now() + 1000ms);
  // To 0 ms: 650 -> 500, 150 units at 400/s = 375 ms, arriving 10.42 ms after the scrub.
  const io::TimePoint t0 = xarm.clock.now();
  xarm.follower->report({0, PlayheadMode::Scrubbed, false});
  xarm.run_until(t0 + 100ms);
  // 100 ms later, back to 750 ms (650). The move arrives at t0 + 110.42 ms, when the base is at
  // 650 - 150 x 100 / 375 = 610; 15 ms later it is at 604: 46 units, 115 ms at 400/s. (Timed
  // from t0 + 100 ms, as it is written, the farthest would be 608.2 and the move 105 ms.)
  xarm.follower->report({750, PlayheadMode::Scrubbed, false});
  const std::vector<Move> moves = xarm.moves();
  ASSERT_EQ(moves.size(), 3u);
  EXPECT_EQ(moves[1].targets, (std::map<std::uint8_t, std::uint16_t>{{kBase, 500}}));
  EXPECT_EQ(moves[1].time_ms, 375);
  const double arrived_ms = std::chrono::duration<double, std::milli>(moves[1].at - t0).count();
  EXPECT_NEAR(arrived_ms, 10.42, 0.01);
  EXPECT_EQ(moves[2].targets, (std::map<std::uint8_t, std::uint16_t>{{kBase, 650}}));
  EXPECT_EQ(moves[2].time_ms, 115);
}

TEST(RobotFollower, TheFirstSlewIsTimedFromWhereTheServosSayTheyStand) {
  const compiler::CompileOutput dance = compile_text(kSlowBase);
  ASSERT_NE(dance.servo_program(), nullptr) << diagnostics_of(dance);
  Xarm xarm(dance, 300);
  // The base reads 300: to 550 is 250 units, 625 ms at 400/s (from home it would be 125 ms).
  const FollowerState s = xarm.follower->report({250, PlayheadMode::Scrubbed, false});
  const std::vector<Move> moves = xarm.moves();
  ASSERT_EQ(moves.size(), 2u);  // the one given by hand, then the slew
  EXPECT_EQ(moves[1].targets, (std::map<std::uint8_t, std::uint16_t>{{kBase, 550}}));
  EXPECT_EQ(moves[1].time_ms, 625);
  EXPECT_NEAR(s.slew_until_ms, 250 + 10.42 + 625, 0.01);
}

// Three steps of 500 ms: base to 700; base to 300 with the claw to 400; base to 500.
const char* const kThreeSteps =
    "robot: xarm\n"
    "sequence:\n"
    "  - move: {base: 700}\n"
    "    time: 500ms\n"
    "    ease: linear\n"
    "  - move: {base: 300, claw: 400}\n"
    "    time: 500ms\n"
    "    ease: linear\n"
    "  - move: {base: 500}\n"
    "    time: 500ms\n"
    "    ease: linear\n";

TEST(RobotFollower, PlayingFromZeroSendsEachMoveAsItsStepStarts) {
  const compiler::CompileOutput dance = compile_text(kThreeSteps);
  ASSERT_NE(dance.servo_program(), nullptr) << diagnostics_of(dance);
  ASSERT_EQ(dance.servo_program()->keyframes.size(), 3u);
  Xarm xarm(dance);
  const io::TimePoint start = xarm.clock.now();
  const FollowerState s = xarm.follower->report({0, PlayheadMode::Playing, false});
  EXPECT_FALSE(s.slewing);
  xarm.run_until(start + 2s);
  const std::vector<Move> moves = xarm.moves();
  ASSERT_EQ(moves.size(), 3u);
  EXPECT_EQ(moves[0].targets.at(kBase), 700);
  EXPECT_EQ(moves[1].targets.at(kBase), 300);
  EXPECT_EQ(moves[1].targets.at(kClaw), 400);
  // Changed servos only: the claw stays at 400.
  EXPECT_EQ(moves[2].targets, (std::map<std::uint8_t, std::uint16_t>{{kBase, 500}}));
  // The first leaves at once (arriving 10 bytes later at 9600 baud, or 13 with the claw); the
  // others arrive by their step's start, no more than a whole move's wire time (16 bytes,
  // 16.7 ms) early.
  EXPECT_LE(moves[0].at, start + 17ms);
  for (std::size_t i = 1; i < 3; ++i) {
    const io::TimePoint due = start + std::chrono::milliseconds(500 * i);
    EXPECT_LE(moves[i].at, due) << i;
    EXPECT_GE(moves[i].at, due - 17ms) << i;
    EXPECT_EQ(moves[i].time_ms, 500) << i;
  }
}

TEST(RobotFollower, APauseSendsNothing) {
  const compiler::CompileOutput dance = compile_text(kThreeSteps);
  ASSERT_NE(dance.servo_program(), nullptr) << diagnostics_of(dance);
  Xarm xarm(dance);
  const io::TimePoint start = xarm.clock.now();
  xarm.follower->report({0, PlayheadMode::Playing, false});
  xarm.run_until(start + 600ms);
  ASSERT_EQ(xarm.moves().size(), 2u);
  const std::size_t frames = xarm.controller.received().size();
  const FollowerState s = xarm.follower->report({600, PlayheadMode::Paused, false});
  EXPECT_FALSE(s.slewing);
  xarm.run_until(start + 3s);
  xarm.follower->report({600, PlayheadMode::Paused, false});
  xarm.run_until(start + 4s);
  EXPECT_EQ(xarm.controller.received().size(), frames);
}

TEST(RobotFollower, ALoopWrapSlewsBackToWhereTheDanceWillBe) {
  const compiler::CompileOutput dance = compile_text(kSlowBase);
  ASSERT_NE(dance.servo_program(), nullptr) << diagnostics_of(dance);
  Xarm xarm(dance);
  const io::TimePoint start = xarm.clock.now();
  xarm.follower->report({0, PlayheadMode::Playing, false});
  xarm.run_until(start + 1500ms);
  ASSERT_EQ(xarm.moves().size(), 1u);  // the wait re-sends nothing
  // The base stands at 700; the page loops back to 0 and plays on. From 700 to the dance at
  // 20 ms (504) is 196 units, 490 ms at 400/s; by 490 ms the dance is at 500 + 200 x 0.49 = 598,
  // 102 units away (255 ms), which the 490 ms cover: a 490 ms move to 598.
  const FollowerState s = xarm.follower->report({0, PlayheadMode::Playing, true});
  EXPECT_TRUE(s.slewing);
  EXPECT_NEAR(s.slew_until_ms, 10.42 + 490, 0.01);
  std::vector<Move> moves = xarm.moves();
  ASSERT_EQ(moves.size(), 2u);
  EXPECT_EQ(moves[1].targets, (std::map<std::uint8_t, std::uint16_t>{{kBase, 598}}));
  EXPECT_EQ(moves[1].time_ms, 490);
  EXPECT_GE(moves[1].time_ms, (700 - 598) * 1000 / 400);
  // Then the rest of the step from where the dance is as the slew ends (500.42 ms), written
  // 10.42 ms before so that it arrives then: to 700 in 1000 - 500.42 ms, 500 ms whole.
  xarm.run_until(xarm.clock.now() + 600ms);
  moves = xarm.moves();
  ASSERT_EQ(moves.size(), 3u);
  EXPECT_EQ(moves[2].targets, (std::map<std::uint8_t, std::uint16_t>{{kBase, 700}}));
  EXPECT_EQ(moves[2].time_ms, 500);
  const double apart = std::chrono::duration<double, std::milli>(moves[2].at - moves[1].at).count();
  EXPECT_NEAR(apart, 490, 0.001);
}

TEST(RobotFollower, ASavedFileMovesTheRobotToTheNewDance) {
  const compiler::CompileOutput dance = compile_text(kSlowBase);
  ASSERT_NE(dance.servo_program(), nullptr) << diagnostics_of(dance);
  Xarm xarm(dance);
  xarm.follower->report({1500, PlayheadMode::Scrubbed, false});
  xarm.run_until(xarm.clock.now() + 1s);
  ASSERT_EQ(xarm.moves().size(), 1u);  // to 700: 200 units, 500 ms
  xarm.follower->report({1500, PlayheadMode::Paused, false});
  // The file now sends the base to 600: held at 1500 ms, the robot goes there (100 units at
  // 400/s: 250 ms).
  std::string text = kSlowBase;
  text.replace(text.find("700"), 3, "600");
  const compiler::CompileOutput saved = compile_text(text);
  ASSERT_NE(saved.servo_program(), nullptr) << diagnostics_of(saved);
  xarm.follower->set_program(saved);
  const std::vector<Move> moves = xarm.moves();
  ASSERT_EQ(moves.size(), 2u);
  EXPECT_EQ(moves[1].targets, (std::map<std::uint8_t, std::uint16_t>{{kBase, 600}}));
  EXPECT_EQ(moves[1].time_ms, 250);
}

TEST(RobotFollower, StopSendsNoMoreMoves) {
  const compiler::CompileOutput dance = compile_text(kThreeSteps);
  ASSERT_NE(dance.servo_program(), nullptr) << diagnostics_of(dance);
  Xarm xarm(dance);
  const io::TimePoint start = xarm.clock.now();
  xarm.follower->report({0, PlayheadMode::Playing, false});
  xarm.run_until(start + 100ms);
  ASSERT_EQ(xarm.moves().size(), 1u);
  const std::size_t frames = xarm.controller.received().size();
  xarm.follower->stop();
  xarm.run_until(start + 3s);
  // A servo controller has no stop for live moves: the servos finish the move they were given.
  EXPECT_EQ(xarm.controller.received().size(), frames);
}

// A serial line at 9600 baud whose write returns at once, as a real port's does, recording when
// each write began and how long it is.
class QueuingLine final : public io::Transport {
 public:
  explicit QueuingLine(io::Clock& clock) : clock_(clock) {}
  Status write(ByteView bytes) override {
    writes.push_back({clock_.now(), bytes.size()});
    return Ok{};
  }
  io::ReadResult read(std::span<std::uint8_t>, io::TimePoint deadline) override {
    clock_.sleep_until(deadline);
    return {};
  }
  void discard_input() override {}
  std::string describe() const override { return "a queuing line"; }
  double seconds_per_byte() const override { return 10.0 / 9600; }

  struct Write {
    io::TimePoint at{0};
    std::size_t bytes = 0;
  };
  std::vector<Write> writes;

 private:
  io::Clock& clock_;
};

TEST(RobotFollower, ADenseDanceNeverQueuesMoreThanTheLineCarries) {
  // Six servos moving every 20 ms: a six-servo move is 25 bytes, 26 ms at 9600 baud.
  std::string text = "robot: xarm\nsequence:\n  - repeat: 50\n    do:\n";
  for (const char* to : {"510", "500"}) {
    text += std::string("      - move: {claw: ") + to + ", wrist_roll: " + to +
            ", wrist_pitch: " + to + ", elbow: " + to + ", shoulder: " + to + ", base: " + to +
            "}\n        time: 20ms\n        ease: linear\n";
  }
  const compiler::CompileOutput dance = compile_text(text);
  ASSERT_NE(dance.servo_program(), nullptr) << diagnostics_of(dance);
  ASSERT_EQ(dance.servo_program()->keyframes.size(), 100u);
  io::ManualClock clock;
  QueuingLine line(clock);
  FollowerOptions options;
  options.read_positions = false;  // the line answers nothing
  RobotFollower follower(*boards::find_board("xarm"), line, clock, options);
  follower.set_program(dance);
  follower.report({0, PlayheadMode::Playing, false});
  for (int guard = 0; guard < 10000; ++guard) {
    const std::optional<io::TimePoint> next = follower.service();
    if (!next) break;
    clock.sleep_until(std::max(*next, clock.now() + 1ms));
  }
  ASSERT_GE(line.writes.size(), 2u);
  // Each write begins once the one before has left: never more than one frame on the line.
  for (std::size_t i = 1; i < line.writes.size(); ++i) {
    const io::Duration wire =
        std::chrono::microseconds(line.writes[i - 1].bytes * 10'000'000 / 9600);
    EXPECT_GE(line.writes[i].at - line.writes[i - 1].at, wire - 1us) << i;
  }
  // Moves were dropped rather than fallen behind: fewer than the 100 keyframes, and the last
  // leaves within one frame's wire time of the dance's last step (1980 ms).
  EXPECT_LT(line.writes.size(), 100u);
  EXPECT_LE(line.writes.back().at, io::TimePoint{1980ms + 27ms});
}

// The car: the gimbal to 1500/1500 in 100 ms, then 1 s driving forward at 10 while the gimbal
// pans to 2000 in 50 steps of 20 ms (step k at 100 + 20 (k - 1) ms carries 1500 + 10 k).
const char* const kCar =
    "robot: raspblock\n"
    "sequence:\n"
    "  - move: {pan: 1500, tilt: 1500}\n"
    "    time: 100ms\n"
    "  - drive: {y: 10}\n"
    "    move: {pan: 2000, tilt: 1500}\n"
    "    time: 1000ms\n"
    "    ease: linear\n";

// The car's state changes in the emulator, as (time, field, value).
std::vector<std::tuple<io::TimePoint, emu::RaspblockField, int>> changes_of(
    const emu::RaspblockEmulator& car) {
  std::vector<std::tuple<io::TimePoint, emu::RaspblockField, int>> out;
  for (const emu::RaspblockChange& c : car.timeline()) out.emplace_back(c.at, c.field, c.value);
  return out;
}

TEST(RobotFollower, TheCarGetsItsPacketsAtTheirTimes) {
  const compiler::CompileOutput dance = compile_text(kCar);
  ASSERT_NE(dance.raspblock_program(), nullptr) << diagnostics_of(dance);
  const boards::Board& board = *boards::find_board("raspblock");
  io::ManualClock clock;
  boards::OpenResult opened = boards::open_port({"emu:raspblock", &board}, clock);
  ASSERT_TRUE(opened.port.has_value());
  RobotFollower follower(board, *opened.port->transport, clock);
  follower.set_program(dance);
  follower.report({0, PlayheadMode::Playing, false});
  for (int guard = 0; guard < 10000; ++guard) {
    const std::optional<io::TimePoint> next = follower.service();
    if (!next) break;
    clock.sleep_until(*next);
  }
  const auto changes = changes_of(*opened.port->raspblock);
  using F = emu::RaspblockField;
  const auto at = [&](F field, int value) -> std::optional<io::TimePoint> {
    for (const auto& [t, f, v] : changes) {
      if (f == field && v == value) return t;
    }
    return std::nullopt;
  };
  EXPECT_EQ(at(F::GimbalHorizontal, 1500), io::TimePoint{0ms});
  EXPECT_EQ(at(F::RockerY, 10), io::TimePoint{100ms});
  EXPECT_EQ(at(F::GimbalHorizontal, 1510), io::TimePoint{100ms});   // step 1
  EXPECT_EQ(at(F::GimbalHorizontal, 1760), io::TimePoint{600ms});   // step 26
  EXPECT_EQ(at(F::GimbalHorizontal, 2000), io::TimePoint{1080ms});  // step 50
  EXPECT_EQ(at(F::RockerY, 0), io::TimePoint{1100ms});              // the stream's stop
}

TEST(RobotFollower, TheStudiosFollowerRunsOnTheRealClock) {
  // make_robot_follower's thread sends the car's packets on io::SteadyClock: 300 ms after the
  // page plays a 100 ms drive, the drive and its stop have gone out. The emulator is read once
  // the follower (and its thread) is gone.
  const compiler::CompileOutput dance =
      compile_text("robot: raspblock\nsequence:\n  - drive: {x: 5}\n    time: 100ms\n");
  ASSERT_NE(dance.raspblock_program(), nullptr) << diagnostics_of(dance);
  const boards::Board& board = *boards::find_board("raspblock");
  io::SteadyClock clock;
  boards::OpenResult opened = boards::open_port({"emu:raspblock", &board}, clock);
  ASSERT_TRUE(opened.port.has_value());
  {
    auto sink = make_robot_follower(board, *opened.port->transport, clock);
    sink->set_program(dance);
    sink->report({0, PlayheadMode::Playing, false});
    clock.sleep_until(clock.now() + 300ms);
  }
  auto changes = changes_of(*opened.port->raspblock);
  std::erase_if(changes,
                [](const auto& c) { return std::get<1>(c) != emu::RaspblockField::RockerX; });
  ASSERT_EQ(changes.size(), 2u);
  EXPECT_EQ(std::get<2>(changes[0]), 5);
  EXPECT_EQ(std::get<2>(changes[1]), 0);
  // The stop left at 100 ms after the drive, give or take the thread's wake-up.
  const double apart =
      std::chrono::duration<double, std::milli>(std::get<0>(changes[1]) - std::get<0>(changes[0]))
          .count();
  EXPECT_NEAR(apart, 100, 20);
}

TEST(RobotFollower, TheCarRefusesToScrubItsDriveButMovesItsGimbal) {
  const compiler::CompileOutput dance = compile_text(kCar);
  ASSERT_NE(dance.raspblock_program(), nullptr) << diagnostics_of(dance);
  const boards::Board& board = *boards::find_board("raspblock");
  io::ManualClock clock;
  boards::OpenResult opened = boards::open_port({"emu:raspblock", &board}, clock);
  ASSERT_TRUE(opened.port.has_value());
  const emu::RaspblockEmulator& car = *opened.port->raspblock;
  RobotFollower follower(board, *opened.port->transport, clock);
  follower.set_program(dance);
  const auto run_until = [&](io::TimePoint until) {
    for (int guard = 0; guard < 10000; ++guard) {
      const std::optional<io::TimePoint> next = follower.service();
      if (!next || *next > until) break;
      clock.sleep_until(std::max(*next, clock.now()));
    }
    clock.sleep_until(until);
  };
  follower.report({0, PlayheadMode::Playing, false});
  run_until(610ms);
  // At 600 ms: driving at 10, the gimbal at step 26 (sent at 600 ms): 1760.
  EXPECT_EQ(car.value(emu::RaspblockField::RockerY), 10);
  EXPECT_EQ(car.value(emu::RaspblockField::GimbalHorizontal), 1760);
  const std::size_t before = car.packets().size();
  // Dragged back to 300 ms: step 11, 1610. The drive stops and says why; the gimbal slews the
  // 150 us at 4166.7 us/s (36 ms) in two steps of 20 ms: 1685 now, 1610 at 18 ms.
  const FollowerState s = follower.report({300, PlayheadMode::Scrubbed, false});
  EXPECT_EQ(s.notices.size(), 1u);
  EXPECT_TRUE(s.slewing);
  EXPECT_EQ(car.value(emu::RaspblockField::RockerY), 0);
  EXPECT_EQ(car.value(emu::RaspblockField::GimbalHorizontal), 1685);
  run_until(clock.now() + 100ms);
  EXPECT_EQ(car.value(emu::RaspblockField::GimbalHorizontal), 1610);
  // Dragged on, to 400 ms (step 16, 1660): the page was told already.
  EXPECT_TRUE(follower.report({400, PlayheadMode::Scrubbed, false}).notices.empty());
  run_until(clock.now() + 100ms);
  EXPECT_EQ(car.value(emu::RaspblockField::GimbalHorizontal), 1660);
  follower.report({300, PlayheadMode::Scrubbed, false});
  run_until(clock.now() + 100ms);
  EXPECT_EQ(car.value(emu::RaspblockField::GimbalVertical), 1500);
  for (std::size_t i = before; i < car.packets().size(); ++i) {
    if (const auto* r = std::get_if<raspblock::Rocker>(&car.packets()[i].packet)) {
      EXPECT_EQ(*r, (raspblock::Rocker{0, 0, 0})) << i;
    }
  }
  // Played again from there, it drives again.
  follower.report({300, PlayheadMode::Playing, false});
  run_until(clock.now() + 50ms);
  EXPECT_EQ(car.value(emu::RaspblockField::RockerY), 10);
  // And stop() sends the board's stop.
  follower.stop();
  EXPECT_EQ(car.value(emu::RaspblockField::RockerY), 0);
}

}  // namespace
}  // namespace seqc::studio
