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

// The three MultiServoMove frames, by hand: 03 count=3 timeLo timeHi {id posLo posHi}, with
// 00 ff (0xff00) for a servo the step does not mention.
const char* const kMoves[] = {
    "55 55 0e 03 03 f4 01 01 c8 00 04 00 ff 06 bc 02",
    "55 55 0e 03 03 e8 03 01 00 ff 04 2c 01 06 00 ff",
    "55 55 0e 03 03 fa 00 01 90 01 04 00 ff 06 00 ff",
};

TEST(DevicePlay, StreamsEachKeyframeAtItsStart) {
  DeviceHarness h;
  h.files.add("try.yaml", kProgram);
  const io::TimePoint start = h.clock.now();
  RunResult r = h.run({"play", "try.yaml", "--port", "emu:xarm"});
  ASSERT_EQ(r.code, 0) << r.err;

  // A battery check first (is a controller there?), then the moves.
  const auto& got = h.emu.received();
  ASSERT_EQ(got.size(), 4u);
  EXPECT_EQ(to_hex(got[0].raw), hex("55 55 02 0f"));
  const milliseconds send_at[] = {milliseconds(0), milliseconds(500), milliseconds(1500)};
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(to_hex(got[i + 1].raw), hex(kMoves[i])) << i;
    EXPECT_EQ(got[i + 1].at - start, send_at[i]) << i;
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

TEST(DevicePlay, NoControllerIsADeviceFailureBeforeAnyMove) {
  emu::XArmConfig config;
  config.faults.silent_after = 0;
  DeviceHarness h(config);
  h.files.add("try.yaml", kProgram);
  RunResult r = h.run({"play", "try.yaml", "--port", "emu:xarm"});
  EXPECT_EQ(r.code, 4);
  EXPECT_EQ(h.received(), hex("55 55 02 0f"));
  EXPECT_NE(r.err.find("seqc: error: no reply from the controller on emu:xarm"), std::string::npos)
      << r.err;
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
