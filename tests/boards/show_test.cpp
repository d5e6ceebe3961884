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

namespace seqc::boards {
namespace {

using std::chrono::milliseconds;

compiler::CompileOutput compile_example(const char* name) {
  io::DiskFileReader files;
  return compiler::compile_file(std::string(SEQC_SOURCE_DIR) + "/examples/" + name, files);
}

struct Stage {
  compiler::CompileOutput walk = compile_example("walk.yaml");
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

}  // namespace
}  // namespace seqc::boards
