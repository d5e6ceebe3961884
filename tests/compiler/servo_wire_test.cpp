// The servo-controller back end: actions, the download plan, live moves, decode round trips and
// the simulator.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "compiler/compile.hpp"
#include "compiler/formats/decode.hpp"
#include "compiler/formats/listing.hpp"
#include "compiler/formats/simulate.hpp"
#include "compiler/frontend/file_loader.hpp"
#include "compiler/frontend/profiles.hpp"
#include "compiler/frontend/reporter.hpp"
#include "compiler/frontend/robot_section.hpp"
#include "compiler/targets/servo_controller/servo_lowering.hpp"
#include "compiler/targets/servo_controller/servo_wire.hpp"
#include "protocol/lsc/lsc_stream.hpp"
#include "runtime/io/disk.hpp"
#include "tests/compiler/lang_test_util.hpp"

namespace seqc::compiler {
namespace {

using compiler::testing::compile_text;
using compiler::testing::program_of;

std::string n_actions(int n) {
  return "robot: lsc-32\nsequence:\n  - move: {ch0: 1000}\n    time: 1s\n  - repeat: " +
         std::to_string(n - 1) + "\n    do:\n      - wait: 20ms\n";
}

TEST(Backend, ActionsMirrorKeyframes) {
  auto out = compile_text(
      "robot: xarm\nsequence:\n  - move: {claw: 100, base: 900}\n    time: "
      "700ms\n  - wait: 40ms\n");
  const auto actions = to_actions(program_of(out));
  ASSERT_EQ(actions.size(), 2u);
  EXPECT_EQ(actions[0], (lsc::GroupAction{700, {{1, 100}, {6, 900}}}));
  EXPECT_EQ(actions[1], (lsc::GroupAction{40, {{1, 100}, {6, 900}}}));
}

TEST(Backend, SmallPlanIsByteExact) {
  // Written by hand from docs/protocol/servo-controller.md: group 2, one action of 700 ms moving
  // servo 1 to 100 (64 00) and servo 6 to 900 (84 03).
  auto out = compile_text(
      "robot: xarm\nsequence:\n  - move: {claw: 100, base: 900}\n    time: "
      "700ms\n");
  auto plan = plan_download(program_of(out), 2);
  ASSERT_TRUE(plan) << plan.error().message;
  EXPECT_EQ(render_hex(*plan),
            "55 55 05 05 01 02 01\n"
            "55 55 07 05 02 02 00 01 00\n"
            "55 55 06 05 03 02 00 00\n"
            "55 55 0f 05 04 02 00 00 0b bc 02 01 64 00 06 84 03\n"
            "55 55 04 05 05 02\n");
  EXPECT_EQ((*plan)[3].keyframe, std::optional<std::size_t>(0));
  EXPECT_FALSE((*plan)[4].keyframe);
}

TEST(Backend, FullGroupPacksIntoExactlyFourBlocks) {
  auto out = compile_text(n_actions(1020));
  const compiler::ServoProgram& p = program_of(out);
  ASSERT_EQ(p.keyframes.size(), 1020u);
  auto plan = plan_download(p, 0);
  ASSERT_TRUE(plan) << plan.error().message;
  ASSERT_EQ(plan->size(), 1u + 4u + 1u + 1020u + 1u);
  const auto& open = std::get<lsc::GroupDownloadOpen>(std::get<lsc::Request>((*plan)[0].request));
  EXPECT_EQ(open.block_counts, (std::vector<std::uint8_t>{255, 255, 255, 255}));
  for (int b = 0; b < 4; ++b) {
    const auto& size =
        std::get<lsc::GroupDownloadSize>(std::get<lsc::Request>((*plan)[1 + b].request));
    EXPECT_EQ(size.block, b);
    EXPECT_EQ(size.count, 255);
  }
  EXPECT_EQ(
      std::get<lsc::GroupDownloadBlocks>(std::get<lsc::Request>((*plan)[5].request)).block_count,
      4);
  const auto& last =
      std::get<lsc::GroupDownloadAction>(std::get<lsc::Request>((*plan)[1025].request));
  EXPECT_EQ(last.block, 3);
  EXPECT_EQ(last.index, 254);
}

TEST(Backend, TheOneThousandAndTwentyFirstActionIsRefused) {
  auto out = compile_text(n_actions(1021));
  EXPECT_FALSE(out.program);
  ASSERT_EQ(out.diagnostics.error_count(), 1u);
  EXPECT_NE(out.diagnostics.all()[0].message.find("1021/1020 actions"), std::string::npos);
}

TEST(Backend, LiveMovesNameEveryUsedServo) {
  auto out = compile_text(R"(robot: xarm
sequence:
  - move: {claw: 100, base: 900}
    time: 700ms
  - move: {elbow: 300}
    time: 300ms
)");
  const auto moves = live_moves(program_of(out));
  ASSERT_EQ(moves.size(), 2u);
  EXPECT_EQ(moves[1].send_ms, 700u);
  EXPECT_EQ(moves[1].move.time_ms, 300);
  using E = lsc::MultiServoMove::Entry;
  EXPECT_EQ(moves[1].move.servos, (std::vector<E>{{1, std::nullopt}, {4, 300}, {6, std::nullopt}}));
  auto bytes = lsc::encode_serial(lsc::Request{moves[1].move});
  ASSERT_TRUE(bytes);
  EXPECT_EQ(to_hex(*bytes), "55 55 0e 03 03 2c 01 01 00 ff 04 2c 01 06 00 ff");
}

// compile -> frames -> hex text -> bytes -> frames -> requests == the program's keyframes.
TEST(Backend, ExamplesRoundTripThroughHex) {
  for (const char* name : {"walk", "wave", "dance"}) {
    SCOPED_TRACE(name);
    io::DiskFileReader disk;
    auto out =
        compiler::compile_file(std::string(SEQC_SOURCE_DIR) + "/examples/" + name + ".yaml", disk);
    const compiler::ServoProgram& p = program_of(out);
    auto plan = plan_download(p, 7);
    ASSERT_TRUE(plan) << plan.error().message;
    auto bytes = parse_hex(render_hex(*plan));
    ASSERT_TRUE(bytes);
    lsc::FrameDecoder decoder;
    decoder.feed(*bytes);
    std::vector<lsc::GroupAction> decoded;
    while (auto frame = decoder.next()) {
      auto request = lsc::decode_request(*frame);
      ASSERT_TRUE(request) << request.error().message;
      if (auto* a = std::get_if<lsc::GroupDownloadAction>(&*request)) {
        EXPECT_EQ(a->group, 7);
        decoded.push_back({a->time_ms, a->servos});
      }
    }
    EXPECT_EQ(decoder.skipped_bytes(), 0u);
    EXPECT_EQ(decoded, to_actions(p));
    DecodeResult table = decode_frames(*bytes);
    EXPECT_TRUE(table.issues.empty()) << table.table;
    EXPECT_EQ(table.actions, p.keyframes.size());
  }
}

TEST(Backend, DecodeFlagsASkippedIndex) {
  auto bytes = parse_hex(
      "55 55 05 05 01 00 02\n55 55 07 05 02 00 00 02 00\n55 55 06 05 03 00 00 00\n"
      "55 55 0c 05 04 00 00 01 0b f4 01 01 f4 01\n");
  ASSERT_TRUE(bytes);
  DecodeResult r = decode_frames(*bytes);
  EXPECT_EQ(r.issues, (std::vector<std::string>{
                          "frame 4: expected block 0 index 0 next, got block 0 index 1",
                          "frame 4: group 0 download was opened but never closed (step 5 "
                          "missing)"}));
}

TEST(Backend, SimulatorMovesInStraightLinesFromHome) {
  auto out = compile_text(R"(robot: xarm
sequence:
  - move: {claw: 700}
    time: 200ms
  - move: {claw: 300, base: 600}
    time: 400ms
)");
  Simulation sim = simulate(program_of(out), 100);
  EXPECT_EQ(sim.duration_ms, 600u);
  EXPECT_EQ(to_csv(sim),
            // The xArm has a geometry, so its tip ends each row: the arm stands straight up
            // (shoulder, elbow, wrist at their zero, 500), 72+97+96+150 mm over the base axis,
            // wherever the base turns.
            "time_ms,claw,base,tip_x,tip_y,tip_z\n"
            "0,500,500,0.00,0.00,415.00\n"
            "100,600,500,0.00,0.00,415.00\n"
            "200,700,500,0.00,0.00,415.00\n"
            "300,600,525,0.00,0.00,415.00\n"
            "400,500,550,0.00,0.00,415.00\n"
            "500,400,575,0.00,0.00,415.00\n"
            "600,300,600,0.00,0.00,415.00\n");
  Simulation odd = simulate(program_of(out), 250);
  ASSERT_EQ(odd.samples.size(), 4u);  // 0, 250, 500 and the end
  EXPECT_EQ(odd.samples.back().time_ms, 600u);
}

// --compare measures the motion the profile's controller makes. The claw is put at 500 (its
// home, so no motion) for 200 ms, then one action moves it to 510 over 1 s, exactly the intended
// straight line 500 + (t - 200) / 100. The straight-line controller follows it: 0 off. One that
// rounds puts out floor(x + 0.5), 0.5 off wherever the line is half-way between units, first at
// 250 ms (500.5, put out as 501). One that truncates puts out 500 until the line reaches 501,
// 0.99 off first at 299 ms (500.99) and again every 100 ms after.
TEST(Backend, CompareMeasuresTheProgramsControllerModel) {
  auto out = compile_text(
      "robot: xarm\nsequence:\n  - move: {claw: 500}\n    time: 200ms\n  - move: {claw: 510}\n"
      "    time: 1s\n");
  compiler::ServoProgram p = program_of(out);
  ASSERT_EQ(p.keyframes.size(), 2u);
  ASSERT_EQ(p.keyframes[1].start_ms, 200u);
  ASSERT_EQ(p.keyframes[1].time_ms, 1000u);
  EXPECT_EQ(p.controller, compiler::ControllerModel::StraightLine);  // the xarm profile's
  struct Expected {
    compiler::ControllerModel model;
    double largest;
    std::uint32_t at_ms;
  };
  for (const Expected& e : {Expected{compiler::ControllerModel::StraightLine, 0, 0},
                            Expected{compiler::ControllerModel::Rounds, 0.5, 250},
                            Expected{compiler::ControllerModel::Truncates, 0.99, 299}}) {
    p.controller = e.model;
    const std::vector<Difference> d = compare_with_intent(p);
    ASSERT_EQ(d.size(), 1u);
    EXPECT_EQ(d[0].servo, "claw");
    EXPECT_NEAR(d[0].largest, e.largest, 1e-9) << static_cast<int>(e.model);
    EXPECT_EQ(d[0].at_ms, e.at_ms) << static_cast<int>(e.model);
  }
  // The CSV shows what the controller puts out: at 250 ms the line is at 500.5, which the
  // rounding controller puts out as 501 and the truncating one as 500.
  p.controller = compiler::ControllerModel::Rounds;
  EXPECT_EQ(simulate(p, 50).samples[5].positions, std::vector<int>{501});
  p.controller = compiler::ControllerModel::Truncates;
  EXPECT_EQ(simulate(p, 50).samples[5].positions, std::vector<int>{500});
}

// The claw eases sine-in-out 300 -> 700 over 2..3 s while a `path: line` runs, so the line takes
// its curve into its own straight pieces. --compare measures the claw against the curve the file
// wrote, 300 + 400 (1 - cos(pi u)) / 2 with u = (t - 2000) / 1000, not against those pieces (it
// said 0). The largest difference, worked out here from the keyframes (each action a straight
// line from the claw's last target to its own), is what compare_with_intent reports, and it is
// not 0.
TEST(Backend, CompareMeasuresACurveALineTookAgainstTheCurveAsWritten) {
  const auto out = compile_text(R"(robot: xarm
sequence:
  - move: home
    time: 1s
  - move: {tip: {x: 200mm, y: 80mm, z: 100mm}, pitch: 135deg, claw: 300}
    time: 1s
  - together:
      arm:
        - move: {tip: {x: 200mm, y: 80mm, z: 40mm}}
          time: 1s
          path: line
      grip:
        - move: {claw: 700}
          time: 1s
          ease: sine-in-out
)");
  const compiler::ServoProgram& p = program_of(out);
  // The claw (id 1) along the actions, from 300 at 2 s.
  double largest = 0;
  for (int t = 2000; t <= 3000; ++t) {
    double from = 300, got = 300;
    for (const compiler::Keyframe& k : p.keyframes) {
      if (k.start_ms < 2000) continue;
      const auto claw = std::find_if(k.targets.begin(), k.targets.end(),
                                     [](const lsc::ServoTarget& x) { return x.id == 1; });
      if (claw == k.targets.end()) continue;
      const double to = claw->position;
      if (t >= static_cast<int>(k.start_ms + k.time_ms)) {
        from = to;
        got = to;
        continue;
      }
      if (t >= static_cast<int>(k.start_ms)) {
        got = from + (to - from) * (t - static_cast<double>(k.start_ms)) / k.time_ms;
      }
      break;
    }
    const double u = (t - 2000) / 1000.0;
    const double want = 300 + 400 * (1 - std::cos(3.14159265358979 * u)) / 2;
    largest = std::max(largest, std::abs(got - want));
  }
  EXPECT_GT(largest, 0.3);
  const std::vector<Difference> d = compare_with_intent(p);
  const auto claw =
      std::find_if(d.begin(), d.end(), [](const Difference& x) { return x.servo == "claw"; });
  ASSERT_NE(claw, d.end());
  EXPECT_NEAR(claw->largest, largest, 0.01);
}

// main.yaml of `files` loaded with its robot section read: what the driver hands the servo
// target's stages. `file` is null (and `robot` empty) when either cannot be read.
struct StagesInput {
  explicit StagesInput(FileReader& files) : loader(files, sources, diags), reporter(diags) {
    const auto main = loader.load("main.yaml");
    if (!main.ok() || !(**main).root) return;
    file = &**main;
    robot = compiler::parse_robot(*file->root->find("robot"), reporter);
  }
  seqc::SourceManager sources;
  seqc::Diagnostics diags;
  compiler::FileLoader loader;
  compiler::Reporter reporter;
  const compiler::LoadedFile* file = nullptr;
  std::optional<compiler::Robot> robot;
};

// The program carries the robot's model (its profile's, or the file's `controller:`), which
// simulate and --compare read. Every built-in profile names the straight line, which is also the
// program's default, so the copy is seen only through a robot that names another: the xarm with
// each other model. (tests/compiler/controller_model_test.cpp compiles `controller:` itself.)
TEST(Backend, TheProgramCarriesTheRobotsControllerModel) {
  compiler::testing::MemoryFiles files;
  files.files["main.yaml"] = "robot: xarm\nsequence:\n  - move: {claw: 510}\n    time: 1s\n";
  for (const compiler::ControllerModel model :
       {compiler::ControllerModel::Rounds, compiler::ControllerModel::Truncates}) {
    SCOPED_TRACE(static_cast<int>(model));
    StagesInput in(files);
    ASSERT_NE(in.file, nullptr) << seqc::render_all(in.diags, in.sources);
    ASSERT_TRUE(in.robot.has_value()) << seqc::render_all(in.diags, in.sources);
    EXPECT_EQ(in.robot->controller, compiler::ControllerModel::StraightLine);  // the xarm's
    in.robot->controller = model;
    const compiler::ServoProgram p =
        compiler::compile_servo(*in.robot, *in.file, in.loader, in.reporter);
    ASSERT_FALSE(in.diags.has_errors(false)) << seqc::render_all(in.diags, in.sources);
    ASSERT_EQ(p.keyframes.size(), 1u);
    EXPECT_EQ(p.controller, model);
  }
}

// The group's capacity is checked on the fitted actions too: a walk whose lower bound fits can
// still fit to more actions than a group holds (a curve needs more than its step's one). Three
// straight moves, the last turning back (no action can run across the turn), fit to three
// actions; with a capacity of 3 the program keeps them all, with 2 it is an error naming 3/2 and
// keeps the first two.
TEST(Backend, TheFittedActionsAreCheckedAgainstTheGroupsCapacity) {
  compiler::testing::MemoryFiles files;
  files.files["main.yaml"] =
      "robot: xarm\nsequence:\n  - move: {claw: 510}\n    time: 1s\n  - move: {claw: 520}\n"
      "    time: 1s\n  - move: {claw: 510}\n    time: 1s\n";
  for (const std::size_t capacity : {std::size_t{3}, std::size_t{2}}) {
    SCOPED_TRACE(capacity);
    StagesInput in(files);
    ASSERT_NE(in.file, nullptr) << seqc::render_all(in.diags, in.sources);
    ASSERT_TRUE(in.robot.has_value()) << seqc::render_all(in.diags, in.sources);
    compiler::ServoWalk walk =
        compiler::walk_servo_file(*in.robot, *in.file, in.loader, in.reporter);
    ASSERT_TRUE(compiler::ready_to_fit(walk, *in.robot, in.reporter));
    EXPECT_EQ(walk.capacity, 1020u);  // the xarm's: 4 blocks of 255
    walk.capacity = capacity;
    const compiler::FitResult fit = compiler::fit_timeline_on_board(
        walk.timeline, compiler::servo_fit_options(*in.robot, true), 0);
    ASSERT_EQ(fit.actions.size(), 3u);
    const compiler::ServoProgram p = compiler::servo_program(*in.robot, walk, fit, 0, in.reporter);
    if (capacity == 3) {
      EXPECT_FALSE(in.diags.has_errors(false)) << seqc::render_all(in.diags, in.sources);
      EXPECT_EQ(p.keyframes.size(), 3u);
    } else {
      ASSERT_EQ(in.diags.error_count(), 1u);
      EXPECT_NE(in.diags.all()[0].message.find("needs 3/2 actions"), std::string::npos)
          << in.diags.all()[0].message;
      EXPECT_EQ(p.keyframes.size(), 2u);
    }
    EXPECT_EQ(p.group_capacity, capacity);
  }
}

}  // namespace
}  // namespace seqc::compiler
