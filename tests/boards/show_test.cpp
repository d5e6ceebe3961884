// A show through the boards: a stored xArm performer and a streamed car on one clock. Both
// start at the common start; the arm's start is confirmed the xArm way after the streams end;
// an interrupt stops both.
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <vector>

#include "compiler/compile.hpp"
#include "runtime/boards/show.hpp"
#include "runtime/io/disk.hpp"
#include "tests/boards/board_test_util.hpp"

namespace seqc::boards {
namespace {

using test_support::compile_example;

using std::chrono::milliseconds;

struct Stage {
  compiler::CompileOutput walk = compile_example("../tests/data/walk-joints.yaml");
  compiler::CompileOutput car = compile_example("car-dance.yaml");
  io::ManualClock host;
  io::ManualClock emulated;
  emu::XArmEmulator controller{emu::XArmConfig{}};
  OpenedPort arm_port;
  OpenedPort car_port;

  Stage() {
    OpenResult a = open_port({"emu:xarm", &board_for(walk)}, host,
                             Hooks{&controller, nullptr, &emulated, nullptr});
    OpenResult c = open_port({"emu:raspblock", &board_for(car)}, host);
    EXPECT_TRUE(a.port && c.port);
    arm_port = std::move(*a.port);
    car_port = std::move(*c.port);
  }

  // Group 2 stored on the arm, as `seqc show` does before it starts anything.
  void store() {
    const Board& board = board_for(walk);
    auto plan = plan_for(board, walk, 2);
    ASSERT_TRUE(plan.ok());
    upload::UploadOptions options;
    options.group = 2;
    ASSERT_TRUE(
        upload(board, Line{*arm_port.transport, *arm_port.clock}, *plan, options, nullptr).ok());
  }

  std::vector<Performer> performers() {
    return {Performer{"arm", &board_for(walk), &arm_port, &walk, 2},
            Performer{"car", &board_for(car), &car_port, &car, 0}};
  }
};

TEST(BoardsShow, EveryoneStartsAtTheCommonStartAndTheArmConfirms) {
  Stage stage;
  stage.store();
  const std::size_t before = stage.controller.received_bytes().size();
  std::vector<Performer> performers = stage.performers();
  const ShowReport r = perform(performers, stage.host, nullptr, milliseconds(200));
  ASSERT_TRUE(r.error.empty()) << r.error;
  ASSERT_EQ(r.play.end, player::PlayEnd::Completed);
  ASSERT_EQ(r.performers.size(), 2u);
  EXPECT_EQ(r.performers[0].track.first, io::Duration{0});
  EXPECT_EQ(r.performers[1].track.first, io::Duration{0});
  EXPECT_EQ(r.performers[0].track.sent, 1u);
  EXPECT_EQ(r.performers[1].track.sent, stage.car_port.raspblock->packets().size());
  ASSERT_TRUE(r.performers[0].run.has_value());
  EXPECT_TRUE(r.performers[0].run->ok());
  EXPECT_EQ(r.performers[0].run->started, Confirmation::Reported);
  EXPECT_FALSE(r.performers[1].run.has_value());
  // GroupRun 2 once, then the battery check that confirms it.
  const Bytes received = stage.controller.received_bytes();
  EXPECT_EQ(to_hex(ByteView(received).subspan(before)), "55 55 05 06 02 01 00 55 55 02 0f");
  // The lead: the common start is 20 ms after perform() began.
  EXPECT_EQ(r.play.started, io::TimePoint{} + milliseconds(20));
}

TEST(BoardsShow, AnEmptyGroupStartsUnreported) {
  Stage stage;  // nothing stored
  std::vector<Performer> performers = stage.performers();
  const ShowReport r = perform(performers, stage.host, nullptr, milliseconds(200));
  ASSERT_EQ(r.play.end, player::PlayEnd::Completed);
  ASSERT_TRUE(r.performers[0].run.has_value());
  EXPECT_TRUE(r.performers[0].run->ok());
  EXPECT_EQ(r.performers[0].run->started, Confirmation::NotReported);
}

TEST(BoardsShow, AnInterruptStopsEveryPerformer) {
  Stage stage;
  std::atomic<bool> interrupted{true};
  std::vector<Performer> performers = stage.performers();
  const ShowReport r = perform(performers, stage.host, &interrupted, milliseconds(200));
  EXPECT_EQ(r.play.end, player::PlayEnd::Interrupted);
  EXPECT_FALSE(r.performers[0].run.has_value());
  EXPECT_TRUE(r.performers[0].track.stop_sent);
  EXPECT_TRUE(r.performers[1].track.stop_sent);
  EXPECT_EQ(to_hex(stage.controller.received_bytes()), "55 55 02 07");  // GroupStop only
  EXPECT_EQ(stage.car_port.raspblock->packets().size(), 1u);            // the stop
}

// A link that takes `seconds_per_byte` per byte and records, on the shared clock, when each write
// began; it answers nothing.
class TimedLink final : public io::Transport {
 public:
  TimedLink(io::Clock& clock, double seconds_per_byte)
      : clock_(clock), seconds_per_byte_(seconds_per_byte) {}
  Status write(ByteView bytes) override {
    writes.push_back({clock_.now(), Bytes(bytes.begin(), bytes.end())});
    return Ok{};
  }
  io::ReadResult read(std::span<std::uint8_t>, io::TimePoint deadline) override {
    clock_.sleep_until(deadline);
    return {};
  }
  void discard_input() override {}
  std::string describe() const override { return "a timed link"; }
  double seconds_per_byte() const override { return seconds_per_byte_; }

  struct Write {
    io::TimePoint at;
    Bytes bytes;
  };
  std::vector<Write> writes;

 private:
  io::Clock& clock_;
  double seconds_per_byte_;
};

TEST(BoardsShow, EachPerformerStartsWhenItsStartFinishesArriving) {
  compiler::CompileOutput walk = compile_example("../tests/data/walk-joints.yaml");
  compiler::CompileOutput car = compile_example("car-dance.yaml");
  io::ManualClock clock;
  OpenedPort arm_port;
  auto arm_link = std::make_unique<TimedLink>(clock, 10.0 / 9600);
  TimedLink& arm = *arm_link;
  arm_port.transport = std::move(arm_link);
  arm_port.clock = &clock;
  OpenedPort car_port;
  auto car_link = std::make_unique<TimedLink>(clock, 10.0 / 115200);
  TimedLink& wheels = *car_link;
  car_port.transport = std::move(car_link);
  car_port.clock = &clock;
  std::vector<Performer> performers{Performer{"arm", &board_for(walk), &arm_port, &walk, 2},
                                    Performer{"car", &board_for(car), &car_port, &car, 0}};
  const ShowReport r = perform(performers, clock, nullptr, milliseconds(10));
  ASSERT_TRUE(r.error.empty()) << r.error;
  ASSERT_FALSE(arm.writes.empty());
  ASSERT_FALSE(wheels.writes.empty());
  const io::TimePoint start = r.play.started;
  // GroupRun 2: 7 bytes x 10 / 9600 s = 7.291667 ms on the wire, so written that long early.
  EXPECT_EQ(to_hex(arm.writes[0].bytes), "55 55 05 06 02 01 00");
  EXPECT_EQ(arm.writes[0].at, start - std::chrono::nanoseconds(7'291'667));
  // The car's first packet: its bytes x 10 / 115200 s early (0.086806 ms a byte).
  const double car_wire_ms = static_cast<double>(wheels.writes[0].bytes.size()) * 10.0 / 115.2;
  const double car_early_ms =
      std::chrono::duration<double, std::milli>(start - wheels.writes[0].at).count();
  EXPECT_NEAR(car_early_ms, car_wire_ms, 1e-6);
  // Both finish arriving at the start: the arm's last byte and the car's last byte together.
  const auto arrived = [](const TimedLink::Write& w, double bits_per_second) {
    return w.at + std::chrono::nanoseconds(static_cast<long long>(
                      static_cast<double>(w.bytes.size()) * 10.0 / bits_per_second * 1e9 + 0.5));
  };
  EXPECT_LE(std::chrono::abs(arrived(arm.writes[0], 9600) - start), std::chrono::nanoseconds(1));
  EXPECT_LE(std::chrono::abs(arrived(wheels.writes[0], 115200) - start),
            std::chrono::nanoseconds(1));
  // The report says so: each started at the common start.
  EXPECT_EQ(r.performers[0].started(), io::Duration{0});
  EXPECT_EQ(r.performers[1].started(), io::Duration{0});
}

}  // namespace
}  // namespace seqc::boards
