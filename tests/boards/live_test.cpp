// Live play through a board's row, in process: the car's stream, live moves on an xArm after its
// battery check, the LSC-6's moves without one, and a board that is not there.
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <vector>

#include "compiler/compile.hpp"
#include "runtime/boards/live.hpp"
#include "runtime/boards/ports.hpp"
#include "runtime/boards/recording_transport.hpp"
#include "runtime/io/disk.hpp"
#include "tests/boards/board_test_util.hpp"

namespace seqc::boards {
namespace {

using test_support::compile_example;
using test_support::silent;

using std::chrono::milliseconds;

TEST(BoardsPlayLive, TheCarGetsItsStream) {
  const compiler::CompileOutput car = compile_example("car-dance.yaml");
  const Board& board = board_for(car);
  ASSERT_EQ(board.key, "raspblock");
  io::ManualClock host;
  OpenResult opened = open_port({"emu:raspblock", &board}, host);
  ASSERT_TRUE(opened.port.has_value());
  std::vector<std::string> events;
  LiveHooks hooks;
  hooks.checked = [&](const LiveReport&) { events.push_back("checked"); };
  hooks.starting = [&](const LiveReport&) { events.push_back("starting"); };
  std::size_t sent = 0;
  hooks.sent = [&](std::size_t, io::Duration) { ++sent; };
  const LiveReport r =
      play_live(board, car, Line{*opened.port->transport, *opened.port->clock}, false, hooks);
  EXPECT_EQ(r.status, LiveStatus::Played);
  ASSERT_FALSE(r.frames.empty());
  EXPECT_EQ(r.play.sent, r.frames.size());
  EXPECT_EQ(sent, r.frames.size());
  EXPECT_EQ(opened.port->raspblock->packets().size(), r.frames.size());
  EXPECT_EQ(events, (std::vector<std::string>{"checked", "starting"}));
  // No wait for the end: the last frame is the stop, sent at its time.
  EXPECT_EQ(host.now(), r.play.started + r.frames.back().at);
  EXPECT_EQ(r.length_ms, car.raspblock_program()->duration_ms);
  EXPECT_TRUE(r.origins.empty());  // a stream has no moves to name
}

TEST(BoardsPlayLive, AnXarmIsAskedForItsBatteryFirstAndPlayedToTheEnd) {
  const compiler::CompileOutput walk = compile_example("../tests/data/walk-joints.yaml");
  const Board& board = board_for(walk);
  io::ManualClock host;
  io::ManualClock emulated;
  emu::XArmEmulator controller{emu::XArmConfig{}};
  OpenResult opened =
      open_port({"emu:xarm", &board}, host, Hooks{&controller, nullptr, &emulated, nullptr});
  ASSERT_TRUE(opened.port.has_value());
  const LiveReport r =
      play_live(board, walk, Line{*opened.port->transport, *opened.port->clock}, false);
  ASSERT_EQ(r.status, LiveStatus::Played) << static_cast<int>(r.probe.failure);
  EXPECT_EQ(r.play.sent, walk.servo_program()->keyframes.size());
  EXPECT_EQ(to_hex(controller.received_bytes()).substr(0, 11), "55 55 02 0f");
  // Returned once the last move had ended.
  EXPECT_GE(emulated.now(), r.play.started + milliseconds(walk.servo_program()->duration_ms()));
  // The length reported is the program's: its last move's end, not when that move was sent.
  EXPECT_EQ(r.length_ms, walk.servo_program()->duration_ms());
  // One origin per move: each move is sent when its step starts, and names where it is written.
  ASSERT_EQ(r.origins.size(), r.frames.size());
  EXPECT_EQ(r.origins[0].start_ms, 0u);
  for (std::size_t i = 0; i < r.frames.size(); ++i) {
    EXPECT_EQ(milliseconds(r.origins[i].start_ms), r.frames[i].at) << i;
    EXPECT_GT(r.origins[i].source.line, 0u) << i;
  }
}

TEST(BoardsPlayLive, TheLsc6GetsItsMovesAfterTheXarmQuestionGoesUnanswered) {
  const compiler::CompileOutput learm = compile_example("learm.yaml");
  const Board& board = board_for(learm);
  ASSERT_EQ(board.key, "lsc6");
  io::ManualClock host;
  OpenResult opened = open_port({"emu:lsc6", &board}, host);
  ASSERT_TRUE(opened.port.has_value());
  const LiveReport r =
      play_live(board, learm, Line{*opened.port->transport, *opened.port->clock}, false);
  ASSERT_EQ(r.status, LiveStatus::Played);
  EXPECT_EQ(r.play.sent, learm.servo_program()->keyframes.size());
  // GetBatteryVoltage (55 55 02 0f), which the LSC-6 ignores, then the first Move (CMD 03).
  auto& lsc6 = static_cast<emu::Lsc6Emulator&>(*opened.port->controller);
  const Bytes received = lsc6.received_bytes();
  ASSERT_GE(received.size(), 8u);
  EXPECT_EQ(to_hex(Bytes(received.begin(), received.begin() + 4)), "55 55 02 0f");
  EXPECT_EQ(received[7], 0x03);
}

TEST(BoardsPlayLive, NoAnswerToTheProbeSendsNoMove) {
  const compiler::CompileOutput walk = compile_example("../tests/data/walk-joints.yaml");
  io::ManualClock clock;
  AcknowledgingTransport nobody(clock, silent);
  const LiveReport r =
      play_live(board_for(walk), walk, Line{nobody, clock, nullptr, milliseconds(300)}, false);
  EXPECT_EQ(r.status, LiveStatus::NoBoard);
  EXPECT_EQ(r.probe.failure, Failure::NoReply);
  EXPECT_EQ(r.probe.awaiting, "the battery voltage");
  // The battery question, then the LSC-6 question (DownloadAction 19 of group 0, total 1,
  // index 255): both unanswered, so no board at all.
  ASSERT_EQ(nobody.writes().size(), 2u);
  EXPECT_EQ(to_hex(nobody.writes()[0]), "55 55 02 0f");
  EXPECT_EQ(to_hex(nobody.writes()[1]), "55 55 08 19 00 01 ff 00 00 00");
}

TEST(BoardsPlayLive, AnInterruptedPlayStopsTheCar) {
  const compiler::CompileOutput car = compile_example("car-dance.yaml");
  io::ManualClock host;
  OpenResult opened = open_port({"emu:raspblock", &board_for(car)}, host);
  ASSERT_TRUE(opened.port.has_value());
  std::atomic<bool> interrupted{true};
  const LiveReport r =
      play_live(board_for(car), car, Line{*opened.port->transport, host, &interrupted}, false);
  EXPECT_EQ(r.status, LiveStatus::Interrupted);
  EXPECT_TRUE(r.play.stop_sent);
  ASSERT_EQ(opened.port->raspblock->packets().size(), 1u);
}

}  // namespace
}  // namespace seqc::boards
