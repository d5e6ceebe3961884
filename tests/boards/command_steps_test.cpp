// The steps of the device commands that the boards library takes for the CLI, checked against
// the in-process emulators and examples: the uploader's options for what `seqc upload` was
// asked, --resync's cut and its groups, a command's traced link, a show's stages and skew, the
// music session's refusals, what `seqc compile` writes, and the argument parsers the commands
// share. Expectations are worked out by hand.
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <vector>

#include "compiler/formats/pose_text.hpp"
#include "runtime/boards/board_link.hpp"
#include "runtime/boards/clock_calibration.hpp"
#include "runtime/boards/dry_run.hpp"
#include "runtime/boards/first_move.hpp"
#include "runtime/boards/music_session.hpp"
#include "runtime/boards/resync_run.hpp"
#include "runtime/boards/servo_args.hpp"
#include "runtime/boards/show.hpp"
#include "runtime/boards/upload_run.hpp"
#include "runtime/boards/xarm_queries.hpp"
#include "runtime/emulator/xarm_emulator.hpp"
#include "tests/boards/board_test_util.hpp"

namespace seqc::boards {
namespace {

using test_support::compile_example;

using std::chrono::milliseconds;

TEST(BoardsUploadRun, TheRunWaitsForTheDownbeatAndIsGuarded) {
  const compiler::CompileOutput walk = compile_example("walk.yaml");
  const Board& board = board_for(walk);
  std::optional<FirstMoveTooFast> too_fast;
  // --run --music: stored only; the computer sends the run on the downbeat.
  upload::UploadOptions o =
      upload_options({3, 2, true, 5, false, true, false}, board, walk, nullptr, too_fast);
  EXPECT_EQ(o.group, 3);
  EXPECT_EQ(o.retries, 2);
  EXPECT_FALSE(o.run);
  EXPECT_EQ(o.run_times, 5);
  EXPECT_TRUE(static_cast<bool>(o.may_run));
  // A dry run still shows the run; --force drops the guard; no --run, no guard.
  EXPECT_TRUE(
      upload_options({0, 4, true, 1, false, true, true}, board, walk, nullptr, too_fast).run);
  EXPECT_FALSE(static_cast<bool>(
      upload_options({0, 4, true, 1, true, false, false}, board, walk, nullptr, too_fast).may_run));
  EXPECT_FALSE(static_cast<bool>(
      upload_options({0, 4, false, 1, false, false, false}, board, walk, nullptr, too_fast)
          .may_run));
  // A car program has no servos to read.
  const compiler::CompileOutput car = compile_example("car-dance.yaml");
  EXPECT_FALSE(static_cast<bool>(
      upload_options({0, 4, true, 1, false, false, false}, board, car, nullptr, too_fast).may_run));
}

TEST(BoardsUploadRun, ResyncCutNamesItsLastGroup) {
  const compiler::CompileOutput waltz = compile_example("waltz.yaml");
  ASSERT_NE(waltz.servo_program(), nullptr);
  const ResyncCut cut = cut_for_resync(*waltz.servo_program(), 4, 0, 10);
  ASSERT_TRUE(cut.error.empty()) << cut.error;
  ASSERT_FALSE(cut.pieces.empty());
  EXPECT_EQ(cut.last_group, 10 + cut.pieces.size() - 1);
  EXPECT_TRUE(cut.fits());
  // From group 254 every piece after the first would need a group past 254.
  const ResyncCut late = cut_for_resync(*waltz.servo_program(), 4, 0, 254);
  EXPECT_EQ(late.fits(), late.pieces.size() == 1);
  // No bars: the chain, which a dance within one group's 1,020 actions leaves in one piece.
  const ResyncCut whole = cut_for_resync(*waltz.servo_program(), 0, 0, 0);
  ASSERT_TRUE(whole.fits()) << whole.error;
  EXPECT_TRUE(whole.chained);
  ASSERT_EQ(whole.pieces.size(), 1u);
  EXPECT_EQ(whole.pieces[0].keyframes.size(), waltz.servo_program()->keyframes.size());
  EXPECT_EQ(whole.last_group, 0u);
}

TEST(BoardsUploadRun, LatestStartIsTheLatestLateness) {
  ResyncRun r;
  EXPECT_EQ(r.latest_start(), io::Duration{0});
  r.play.lateness = {milliseconds(2), milliseconds(7), milliseconds(3)};
  EXPECT_EQ(r.latest_start(), milliseconds(7));
}

TEST(BoardsLink, OpensTheEmulatorWithTheTimeoutAndSaysWhyNot) {
  const Board& xarm = *find_board("xarm");
  io::ManualClock host, emulated;
  emu::XArmEmulator controller{emu::XArmConfig{}};
  TraceFile untraced;
  ASSERT_TRUE(untraced.open(""));  // no file: the port's own transport
  const BoardLink link =
      open_link({"emu:xarm", &xarm}, untraced, host,
                Hooks{&controller, nullptr, &emulated, nullptr}, nullptr, milliseconds(250));
  ASSERT_TRUE(link.port.has_value());
  ASSERT_TRUE(link.line.has_value());
  EXPECT_EQ(link.transport, link.port->transport.get());
  EXPECT_EQ(&link.line->transport, link.transport);
  EXPECT_EQ(link.line->timeout, milliseconds(250));
  EXPECT_EQ(link.port->clock, &emulated);  // the hooks' clock

  // --force, or a program with no servos to read: nothing is read, nothing is too fast.
  EXPECT_FALSE(run_too_fast(xarm, *link.line, compile_example("walk.yaml"), true));
  EXPECT_FALSE(run_too_fast(xarm, *link.line, compile_example("car-dance.yaml"), false));
  EXPECT_TRUE(controller.received_bytes().empty());

  const BoardLink bad = open_link({"emu:nope", &xarm}, untraced, host, Hooks{}, nullptr);
  EXPECT_FALSE(bad.port.has_value());
  EXPECT_FALSE(bad.line.has_value());
  EXPECT_EQ(bad.failure.problem, PortProblem::Malformed);
  EXPECT_EQ(bad.request.text, "emu:nope");
}

TEST(BoardsShowStages, OpenInOrderAndMeasureTheSkew) {
  compiler::Performer nowhere;
  nowhere.name = "arm";
  nowhere.output = compile_example("walk.yaml");
  io::ManualClock host, emulated;
  emu::XArmEmulator controller{emu::XArmConfig{}};
  const Hooks hooks{&controller, nullptr, &emulated, nullptr};
  ShowStage a;
  EXPECT_EQ(open_stage(nowhere, "", host, hooks, a).problem, StageProblem::NoPort);
  EXPECT_FALSE(a.port.has_value());

  compiler::Performer arm = std::move(nowhere);
  arm.port = "emu:xarm";
  arm.group = 4;
  std::vector<ShowStage> stages(1);
  const StageOpen opened = open_stage(arm, "", host, hooks, stages[0]);
  ASSERT_EQ(opened.problem, StageProblem::None);
  ASSERT_TRUE(stages[0].port.has_value());
  EXPECT_EQ(stages[0].board, &board_for(arm.output));
  const std::vector<Performer> performers = performers_of(stages);
  ASSERT_EQ(performers.size(), 1u);
  EXPECT_EQ(performers[0].name, "arm");
  EXPECT_EQ(performers[0].group, 4);
  EXPECT_EQ(performers[0].port, &*stages[0].port);
  // The stored group goes into the performer's group.
  auto plan = stage_plan(stages[0]);
  ASSERT_TRUE(plan.ok());
  EXPECT_TRUE(upload_stage(stages[0], *plan, nullptr, nullptr).ok());

  // Starts 1 ms (+ 2 ms on the wire) and 5 ms after the common start, one without a first write.
  ShowReport r;
  r.performers.resize(3);
  r.performers[0].track.first = milliseconds(1);
  r.performers[0].wire = milliseconds(2);
  r.performers[1].track.first = milliseconds(5);
  EXPECT_EQ(r.start_skew(), milliseconds(5));  // from the unset one's 0 to 5 ms
}

TEST(BoardsMusicSession, RefusesWithoutAnOutputAndFindsTheFirstWrite) {
  compiler::Song song;
  song.file = "song.wav";
  MusicSession session;
  const MusicOpen r = open_music(song, milliseconds(20), nullptr, nullptr, session);
  EXPECT_EQ(r.status, MusicOpenStatus::NoOutput);
  EXPECT_EQ(session.file, "song.wav");
  EXPECT_EQ(session.audio_offset, milliseconds(20));
  EXPECT_EQ(session.output, nullptr);

  EXPECT_EQ(song_of(compile_example("walk.yaml")), nullptr);
  EXPECT_NE(song_of(compile_example("neon-dance.yaml")), nullptr);

  player::PlayReport play;
  EXPECT_FALSE(first_written(play).has_value());
  play.started = io::TimePoint{milliseconds(100)};
  play.tracks.resize(1);
  play.tracks[0].first = milliseconds(-3);
  EXPECT_EQ(first_written(play), io::TimePoint{milliseconds(97)});
}

TEST(BoardsCompiledText, DryRunOnAStoringBoardRenderElsewhere) {
  const compiler::CompileOutput walk = compile_example("walk.yaml");
  const Board& arm = board_for(walk);
  auto plan = plan_for(arm, walk, 2);
  ASSERT_TRUE(plan.ok());
  upload::UploadOptions options;
  options.group = 2;
  const CompiledText dry = compiled_text(walk, 2, true, Emit::Hex);
  EXPECT_TRUE(dry.error.empty()) << dry.error;
  EXPECT_EQ(dry.text, dry_run(arm, *plan, options).text);
  EXPECT_EQ(compiled_text(walk, 2, false, Emit::Hex).text, *arm.render(walk, Emit::Hex, 2));
  // The car stores nothing: --dry-run lists its program as --emit does.
  const compiler::CompileOutput car = compile_example("car-dance.yaml");
  EXPECT_EQ(compiled_text(car, 0, true, Emit::Listing).text,
            *board_for(car).render(car, Emit::Listing, 0));
}

TEST(BoardsCommandArgs, GroupTargetsServosLengthsAndBusFields) {
  EXPECT_TRUE(parse_group_target("all")->all);
  EXPECT_EQ(parse_group_target("all")->group, 255);
  EXPECT_EQ(parse_group_target("7")->group, 7);
  EXPECT_FALSE(parse_group_target("7")->all);
  EXPECT_FALSE(parse_group_target("255"));

  EXPECT_FALSE(servos_to_read({}, std::nullopt));
  EXPECT_EQ(*servos_to_read({}, *robot_for_profile("xarm")),
            (std::vector<std::uint8_t>{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(*servos_to_read({"3", "1"}, std::nullopt), (std::vector<std::uint8_t>{3, 1}));

  EXPECT_EQ(*parse_run_length("20s"), 20000u);
  EXPECT_EQ(*parse_run_length("1500ms"), 1500u);
  EXPECT_FALSE(parse_run_length("500ms"));
  EXPECT_FALSE(parse_run_length("11min"));
  EXPECT_FALSE(parse_run_length("2 beats"));

  BusServoFields fields;
  fields.position_min = 100;
  fields.led = "off";
  auto changes = checked_changes(fields);
  ASSERT_TRUE(changes);
  EXPECT_EQ(changes->position_min, 100);
  EXPECT_EQ(changes->led_status, 1);
  EXPECT_FALSE(changes->servo.has_value());
  fields.position_max = 70000;
  auto wide = checked_changes(fields);
  ASSERT_FALSE(wide);
  EXPECT_NE(wide.error().message.find("--position-max"), std::string::npos);

  EXPECT_EQ(compiler::next_pose_name("poses:\n  pose1: {a: 1}\n"), "pose2");
  EXPECT_TRUE(compiler::is_pose_name("ready_2"));
  EXPECT_FALSE(compiler::is_pose_name("2ready"));
  EXPECT_FALSE(compiler::is_pose_name("re-ady"));
}

}  // namespace
}  // namespace seqc::boards
