// The session commands of each storing board's row, against its emulator: run (with the board's
// own confirmation), stop, erase and move, and what each sends.
#include <gtest/gtest.h>

#include <chrono>
#include <optional>
#include <vector>

#include "runtime/boards/board.hpp"
#include "runtime/boards/recording_transport.hpp"
#include "runtime/emulator/emulator_transport.hpp"
#include "runtime/emulator/lsc6_emulator.hpp"
#include "runtime/emulator/xarm_emulator.hpp"
#include "protocol/lsc6/lsc6_messages.hpp"
#include "tests/boards/board_test_util.hpp"

namespace seqc::boards {
namespace {

using test_support::silent;

using std::chrono::milliseconds;

const Board& xarm() { return *find_board("xarm"); }
const Board& lsc6() { return *find_board("lsc6"); }

struct Xarm {
  io::ManualClock clock;
  emu::XArmEmulator controller{emu::XArmConfig{}};
  emu::EmulatorTransport transport{controller, clock};
  Line line{transport, clock, nullptr, milliseconds(200)};

  // One action in `group`, stored the way `seqc upload` stores it.
  void store(std::uint8_t group) {
    std::vector<lsc::GroupAction> actions(1);
    actions[0].time_ms = 500;
    actions[0].servos = {{1, 600}};
    auto steps = lsc::plan_group_download(group, actions);
    ASSERT_TRUE(steps.ok());
    auto frames = plan_frames(*steps);
    ASSERT_TRUE(frames.ok());
    upload::UploadOptions options;
    options.group = group;
    const auto r = upload(xarm(), line, Plan{group, 1, std::move(*frames)}, options, nullptr);
    ASSERT_TRUE(r.ok()) << r.message;
  }
};

TEST(XarmRow, RunOfAStoredGroupIsReported) {
  Xarm x;
  x.store(3);
  const std::size_t before = x.controller.received_bytes().size();
  const RunOutcome r = run_group(xarm(), x.line, 3, 2);
  EXPECT_TRUE(r.ok());
  EXPECT_EQ(r.started, Confirmation::Reported);
  // GroupRun 3 twice, then the battery check.
  const Bytes received = x.controller.received_bytes();
  EXPECT_EQ(to_hex(ByteView(received).subspan(before)), "55 55 05 06 03 02 00 55 55 02 0f");
}

TEST(XarmRow, RunOfAnEmptyGroupIsConfirmedButNotReported) {
  Xarm x;
  const RunOutcome r = run_group(xarm(), x.line, 4, 1);
  EXPECT_TRUE(r.ok());
  EXPECT_EQ(r.started, Confirmation::NotReported);
}

TEST(XarmRow, RunNobodyConfirms) {
  io::ManualClock clock;
  AcknowledgingTransport nobody(clock, silent);
  const RunOutcome r = run_group(xarm(), Line{nobody, clock, nullptr, milliseconds(100)}, 1, 3);
  EXPECT_EQ(r.failure, Failure::Unconfirmed);
  EXPECT_EQ(r.request, "GroupRun group=1 times=3");
  EXPECT_EQ(r.attempts, 2);
  // GroupRun, then the battery check twice.
  ASSERT_EQ(nobody.writes().size(), 3u);
  EXPECT_EQ(to_hex(nobody.writes()[0]), "55 55 05 06 01 03 00");
  EXPECT_EQ(to_hex(nobody.writes()[2]), "55 55 02 0f");
}

// A controller that answers GroupStop with the form that names the group (group 5).
Bytes stops_group_five(ByteView request) {
  if (to_hex(request) == "55 55 02 07") {
    return lsc::encode_serial(lsc::Reply{lsc::GroupStopped{lsc::GroupStopped::Detail{5, 1}}})
        .value();
  }
  if (to_hex(request) == "55 55 02 0f") {
    return lsc::encode_serial(lsc::Reply{lsc::BatteryVoltage{7400}}).value();
  }
  return {};
}

TEST(XarmRow, StopSaysWhichGroupStopped) {
  io::ManualClock clock;
  AcknowledgingTransport controller(clock, stops_group_five);
  const StopOutcome s = xarm().stop(Line{controller, clock, nullptr, milliseconds(200)});
  EXPECT_TRUE(s.ok());
  EXPECT_EQ(s.stopped, Confirmation::Reported);
  EXPECT_EQ(s.group, std::optional<std::uint8_t>(5));
}

TEST(XarmRow, StopWithTheDatalessNotice) {
  Xarm x;
  x.store(5);
  ASSERT_TRUE(run_group(xarm(), x.line, 5, 0).ok());
  const StopOutcome s = xarm().stop(x.line);
  EXPECT_TRUE(s.ok());
  EXPECT_EQ(s.stopped, Confirmation::Reported);
  EXPECT_EQ(s.group, std::nullopt);  // the emulator sends 55 55 02 07
}

TEST(XarmRow, EraseOneGroupOrEvery) {
  Xarm x;
  x.store(1);
  x.store(2);
  EXPECT_TRUE(xarm().erase(x.line, 1).ok());
  EXPECT_FALSE(x.controller.stored_group(1).has_value());
  EXPECT_TRUE(x.controller.stored_group(2).has_value());
  EXPECT_TRUE(xarm().erase(x.line, std::nullopt).ok());
  EXPECT_FALSE(x.controller.stored_group(2).has_value());
}

TEST(XarmRow, MoveIsConfirmed) {
  Xarm x;
  const std::vector<lsc::ServoTarget> targets{{1, 500}, {2, 700}};
  EXPECT_TRUE(xarm().move(x.line, targets, 1000).ok());
  // MultiServoMove: 55 55 LEN 03 N tLo tHi {id pLo pHi}, then the battery check.
  EXPECT_EQ(to_hex(x.controller.received_bytes()),
            "55 55 0b 03 02 e8 03 01 f4 01 02 bc 02 55 55 02 0f");
}

struct Lsc6 {
  io::ManualClock clock;
  emu::Lsc6Emulator board{emu::Lsc6Config{}};
  emu::EmulatorTransport transport{board, clock};
  Line line{transport, clock, nullptr, milliseconds(200)};
};

TEST(Lsc6Row, RunIsAnswered) {
  Lsc6 b;
  const RunOutcome r = run_group(lsc6(), b.line, 0, 1);
  EXPECT_TRUE(r.ok());
  EXPECT_EQ(r.started, Confirmation::Reported);
  EXPECT_EQ(to_hex(b.board.received_bytes()), "55 55 05 06 00 01 00");
}

TEST(Lsc6Row, RunNobodyAnswersIsStartedUnconfirmed) {
  io::ManualClock clock;
  AcknowledgingTransport nobody(clock, silent);
  const RunOutcome r = run_group(lsc6(), Line{nobody, clock, nullptr, milliseconds(100)}, 0, 1);
  EXPECT_TRUE(r.ok());
  EXPECT_EQ(r.started, Confirmation::NeverAnswered);
  EXPECT_EQ(clock.now(), io::TimePoint{} + milliseconds(100));
}

TEST(Lsc6Row, StopIsNeverAnswered) {
  Lsc6 b;
  const StopOutcome s = lsc6().stop(b.line);
  EXPECT_TRUE(s.ok());
  EXPECT_EQ(s.stopped, Confirmation::NeverAnswered);
  EXPECT_EQ(to_hex(b.board.received_bytes()), "55 55 02 07");
}

TEST(Lsc6Row, EraseWipesEveryGroupAndRefusesOne) {
  Lsc6 b;
  const Outcome one = lsc6().erase(b.line, 2);
  EXPECT_FALSE(one.ok());
  EXPECT_TRUE(b.board.received_bytes().empty());
  EXPECT_TRUE(lsc6().erase(b.line, std::nullopt).ok());
  EXPECT_EQ(to_hex(b.board.received_bytes()), "55 55 02 08");
}

TEST(Lsc6Row, EraseNobodyAnswersIsNoReply) {
  io::ManualClock clock;
  AcknowledgingTransport nobody(clock, silent);
  const Outcome o = lsc6().erase(Line{nobody, clock, nullptr, milliseconds(100)}, std::nullopt);
  EXPECT_EQ(o.failure, Failure::NoReply);
  EXPECT_EQ(o.awaiting, "the erase confirmation");
}

TEST(Lsc6Row, MoveIsSentUnconfirmed) {
  Lsc6 b;
  const std::vector<lsc::ServoTarget> targets{{1, 1500}};
  EXPECT_TRUE(lsc6().move(b.line, targets, 1000).ok());
  // Move: 55 55 LEN 03 N tLo tHi {id pLo pHi}, nothing after it.
  EXPECT_EQ(to_hex(b.board.received_bytes()), "55 55 08 03 01 e8 03 01 dc 05");
}

TEST(Rows, FirstTooBigFindsTheFirstFrameOverTheLimit) {
  class Small final : public io::Transport {
   public:
    Status write(ByteView) override { return Ok{}; }
    io::ReadResult read(std::span<std::uint8_t>, io::TimePoint) override { return {}; }
    void discard_input() override {}
    std::string describe() const override { return "small"; }
    std::size_t max_frame_bytes() const override { return 8; }
  };
  Plan plan;
  plan.frames.resize(3);
  plan.frames[0].bytes = Bytes(8, 0);
  plan.frames[1].bytes = Bytes(9, 0);
  plan.frames[2].bytes = Bytes(20, 0);
  EXPECT_EQ(first_too_big(plan, Small{}), std::optional<std::size_t>(1));
  io::ManualClock clock;
  AcknowledgingTransport any(clock, silent);
  EXPECT_EQ(first_too_big(plan, any), std::nullopt);
}

}  // namespace
}  // namespace seqc::boards
