// `seqc play FILE` on the servo controller: the program streamed live as MultiServoMove frames,
// each sent at its keyframe's start on the (manual) clock.
#include <gtest/gtest.h>

#include <atomic>

#include "compiler/compile.hpp"
#include "runtime/cli/servo_play.hpp"
#include "runtime/emulator/emulator_transport.hpp"
#include "runtime/upload/controller_link.hpp"
#include "tests/cli/device_test_util.hpp"

namespace seqc::cli::test {
namespace {

using std::chrono::milliseconds;

// Keyframes start at 0, 500 ms and 1500 ms; the program uses servos 1 (claw), 4 (elbow) and
// 6 (base) and ends at 1750 ms.
constexpr const char* kProgram = R"(name: try
robot:
  profile: xarm
sequence:
  - move: {claw: 200, base: 700}
    time: 500ms
  - move: {elbow: 300}
    time: 1s
  - move: {claw: 400}
    time: 250ms
)";

// The three MultiServoMove frames, by hand: 03 count timeLo timeHi {id posLo posHi}, each
// carrying only the servos whose target changes (LEN = 3 + 3 x count + 2).
const char* const kMoves[] = {
    // claw 200 (c8 00) and base 700 (bc 02) over 500 ms (f4 01)
    "55 55 0b 03 02 f4 01 01 c8 00 06 bc 02",
    // elbow 300 (2c 01) over 1000 ms (e8 03)
    "55 55 08 03 01 e8 03 04 2c 01",
    // claw 400 (90 01) over 250 ms (fa 00)
    "55 55 08 03 01 fa 00 01 90 01",
};

// ServoPositionRead of the program's servos: count 3, ids 1, 4, 6 (LEN = 4 + 2).
constexpr const char* kReadPositions = "55 55 06 15 03 01 04 06";

TEST(DevicePlay, StreamsEachKeyframeAtItsStart) {
  DeviceHarness h;
  h.files.add("try.yaml", kProgram);
  const io::TimePoint start = h.clock.now();
  RunResult r = h.run({"play", "try.yaml", "--port", "emu:xarm"});
  ASSERT_EQ(r.code, 0) << r.err;

  // The program's servos read first (where does each first move start?): ServoPositionRead
  // (15) of 1, 4 and 6. Then a battery check (is a controller there?), then the moves.
  const auto& got = h.emu.received();
  ASSERT_EQ(got.size(), 5u);
  EXPECT_EQ(to_hex(got[0].raw), hex(kReadPositions));
  EXPECT_EQ(to_hex(got[1].raw), hex("55 55 02 0f"));
  const milliseconds send_at[] = {milliseconds(0), milliseconds(500), milliseconds(1500)};
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(to_hex(got[i + 2].raw), hex(kMoves[i])) << i;
    EXPECT_EQ(got[i + 2].at - start, send_at[i]) << i;
  }
  // A summary, so on stderr; stdout carries data only.
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("seqc: played 3 moves, 1.75 s; moves left the port late by p50 0.0 ms, "
                       "p99 0.0 ms, max 0.0 ms (measured once each had left)\n"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(h.clock.now() - start, milliseconds(1750));  // returns when the sequence ends

  // The final pose: what the program last set for every servo, the rest where they were.
  const io::TimePoint end = start + milliseconds(1750);
  h.emu.advance_to(end);
  EXPECT_EQ(h.emu.servo_position(1, end), 400);
  EXPECT_EQ(h.emu.servo_position(4, end), 300);
  EXPECT_EQ(h.emu.servo_position(6, end), 700);
  EXPECT_EQ(h.emu.servo_position(2, end), 500);
  // Nothing was stored.
  for (int g = 0; g < 255; ++g) EXPECT_FALSE(h.emu.stored_group(static_cast<std::uint8_t>(g)));
}

// A servo named again at the target it already has is left out; a move in which nothing
// changes still leaves, on time, with one servo sent where it already is.
TEST(DevicePlay, SendsOnlyTheServosThatChange) {
  DeviceHarness h;
  h.files.add("same.yaml", R"(name: same
robot: xarm
sequence:
  - move: {claw: 300, elbow: 600}
    time: 400ms
  - move: {claw: 300, elbow: 650}
    time: 100ms
  - move: {claw: 300, elbow: 650}
    time: 200ms
)");
  const io::TimePoint start = h.clock.now();
  RunResult r = h.run({"play", "same.yaml", "--port", "emu:xarm"});
  ASSERT_EQ(r.code, 0) << r.err;
  auto got = h.emu.received();
  ASSERT_EQ(got.size(), 5u);
  EXPECT_EQ(to_hex(got[0].raw), hex("55 55 05 15 02 01 04"));  // read claw and elbow
  EXPECT_EQ(to_hex(got[1].raw), hex("55 55 02 0f"));
  got.erase(got.begin());  // the rest as if the read had not been there
  // First: both servos it names, claw 300 (2c 01) and elbow 600 (58 02) over 400 ms (90 01).
  EXPECT_EQ(to_hex(got[1].raw), hex("55 55 0b 03 02 90 01 01 2c 01 04 58 02"));
  // Then only the elbow, to 650 (8a 02) over 100 ms (64 00): 10 bytes, not 13.
  EXPECT_EQ(to_hex(got[2].raw), hex("55 55 08 03 01 64 00 04 8a 02"));
  // Nothing changes: the claw, already at 300, over 200 ms (c8 00), at 500 ms.
  EXPECT_EQ(to_hex(got[3].raw), hex("55 55 08 03 01 c8 00 01 2c 01"));
  EXPECT_EQ(got[3].at - start, milliseconds(500));
  EXPECT_EQ(h.clock.now() - start, milliseconds(700));
}

TEST(DevicePlay, NoControllerIsADeviceFailureBeforeAnyMove) {
  emu::XArmConfig config;
  config.faults.silent_after = 0;
  DeviceHarness h(config);
  h.files.add("try.yaml", kProgram);
  RunResult r = h.run({"play", "try.yaml", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 4);
  // The unanswered position read says nothing itself; the probe after it is the failure, and
  // the LSC-6 question (group 0, total 1, index 255) finds no LSC-6 either.
  EXPECT_EQ(h.received(),
            hex(std::string(kReadPositions) + " 55 55 02 0f  55 55 08 19 00 01 ff 00 00 00"));
  EXPECT_NE(r.err.find("seqc: error: no reply from the controller on emu:xarm"), std::string::npos)
      << r.err;
}

// The first move from where the servos are: base at 120 (the emulator posed there), to 880 in
// 400 ms is 760 / 0.4 = 1900 units/s, above the xarm profile's max_speed 1562.5/s (375 deg/s x
// 1000 units / 240 deg). Refused after the read, nothing else sent; --force plays it.
constexpr const char* kFastFirst = R"(name: fast
robot: xarm
sequence:
  - move: {base: 880}
    time: 400ms
)";

TEST(DevicePlay, AFirstMoveTooFastFromWhereTheServoIsIsRefused) {
  DeviceHarness h(base_at(120));
  h.files.add("fast.yaml", kFastFirst);
  RunResult r = h.run({"play", "fast.yaml", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 1);
  const std::string said =
      "seqc: error: 'base' is at 120; reaching 880 in 0.4 s is 1900 units/s, above its max_speed "
      "1562/s; slow the first move or pass --force\n";
  ASSERT_GE(r.err.size(), said.size()) << r.err;
  EXPECT_EQ(r.err.substr(r.err.size() - said.size()), said);
  // Only the read went out (ServoPositionRead of servo 6); the base has not moved.
  EXPECT_EQ(h.received(), hex("55 55 04 15 01 06"));
  EXPECT_EQ(h.emu.servo_position(6, h.clock.now() + milliseconds(1000)), 120);
}

TEST(DevicePlay, AFirstMoveWithinMaxSpeedOrForcedPlays) {
  {
    // From 700: 180 / 0.4 = 450 units/s.
    DeviceHarness h(base_at(700));
    h.files.add("fast.yaml", kFastFirst);
    RunResult r = h.run({"play", "fast.yaml", "--port", "emu:xarm"});
    EXPECT_EQ(r.code, 0) << r.err;
    // The read, the probe, the move: base (6) to 880 (70 03) over 400 ms (90 01).
    EXPECT_EQ(h.received(), hex("55 55 04 15 01 06  55 55 02 0f  55 55 08 03 01 90 01 06 70 03"));
  }
  {
    DeviceHarness h(base_at(120));
    h.files.add("fast.yaml", kFastFirst);
    RunResult r = h.run({"play", "fast.yaml", "--port", "emu:xarm", "--force"});
    EXPECT_EQ(r.code, 0) << r.err;
    // --force reads nothing: the probe and the move.
    EXPECT_EQ(h.received(), hex("55 55 02 0f  55 55 08 03 01 90 01 06 70 03"));
  }
}

// Sets the interrupt flag once `after` writes have gone through (Ctrl-C during a play).
class InterruptAfter final : public io::Transport {
 public:
  InterruptAfter(io::Transport& inner, std::atomic<bool>& flag, int after)
      : inner_(inner), flag_(flag), left_(after) {}
  Status write(ByteView bytes) override {
    Status s = inner_.write(bytes);
    if (--left_ == 0) flag_.store(true);
    return s;
  }
  io::ReadResult read(std::span<std::uint8_t> b, io::TimePoint d) override {
    return inner_.read(b, d);
  }
  void discard_input() override { inner_.discard_input(); }
  std::string describe() const override { return inner_.describe(); }

 private:
  io::Transport& inner_;
  std::atomic<bool>& flag_;
  int left_;
};

TEST(DevicePlay, CtrlCStopsSendingAndSaysWhere) {
  DeviceHarness h;
  h.files.add("try.yaml", kProgram);
  compiler::CompileOutput compiled = compiler::compile_file("try.yaml", h.files);
  ASSERT_NE(compiled.servo_program(), nullptr);

  emu::EmulatorTransport emulated(h.emu, h.clock);
  InterruptAfter port(emulated, h.interrupted, 3);  // the check, move 1, move 2
  const boards::Line line{port, h.clock, &h.interrupted, std::chrono::seconds(1)};
  std::ostringstream out;
  std::ostringstream err;
  Context ctx{out, err, h.clock, h.files};
  ctx.interrupted = &h.interrupted;

  EXPECT_EQ(play_on_line(ctx, compiled, line), ExitCode::Interrupted);
  EXPECT_EQ(h.received(), hex(std::string("55 55 02 0f ") + kMoves[0] + " " + kMoves[1]));
  EXPECT_EQ(out.str(), "");
  EXPECT_EQ(err.str(),
            "seqc: playing 3 moves (1.75 s) live on emu:xarm; Ctrl-C stops\n"
            "seqc: interrupted: stopped sending after step 2 of 3 at 0.5 s (try.yaml:7); the "
            "servos finish the move they were given\n");
}

}  // namespace
}  // namespace seqc::cli::test
