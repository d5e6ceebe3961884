// The table of boards agrees with the other lists that name boards: the compiler's profiles and
// the emulator names `--port emu:NAME` accepts.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "compiler/frontend/profiles.hpp"
#include "runtime/boards/board.hpp"
#include "runtime/transport/port_spec.hpp"

namespace seqc::boards {
namespace {

TEST(BoardTable, EveryProfileNamesABoard) {
  for (const std::string& name : compiler::profile_names()) {
    const compiler::RobotProfile* profile = compiler::find_profile(name);
    ASSERT_NE(profile, nullptr) << name;
    EXPECT_NE(find_board(profile->board), nullptr) << name << " names '" << profile->board << "'";
  }
}

TEST(BoardTable, ProfilesReachTheirBoards) {
  const std::pair<const char*, const char*> expected[] = {
      {"xarm", "xarm"},   {"bus", "xarm"},   {"lsc-16", "xarm"},
      {"lsc-32", "xarm"}, {"lsc-6", "lsc6"}, {"raspblock", "raspblock"},
  };
  for (const auto& [profile, board] : expected) {
    EXPECT_EQ(board_for_device(profile, "").key, board) << profile;
  }
}

TEST(BoardTable, KeysAreUnique) {
  std::set<std::string_view> keys;
  for (const Board* b : all_boards()) EXPECT_TRUE(keys.insert(b->key).second) << b->key;
  EXPECT_EQ(keys.size(), 3u);
}

TEST(BoardTable, EveryEmulatorNameHasExactlyOneBoard) {
  // The names transport/port_spec.cpp accepts after "emu:".
  for (std::string_view name : {"xarm", "xarm-hid", "lsc6", "raspblock"}) {
    ASSERT_TRUE(transport::parse_port("emu:" + std::string(name))) << name;
    int boards = 0;
    for (const Board* b : all_boards()) {
      for (std::string_view e : b->emulators) boards += e == name ? 1 : 0;
    }
    EXPECT_EQ(boards, 1) << name;
    ASSERT_NE(board_for_emulator(name), nullptr) << name;
    EXPECT_NE(board_for_emulator(name)->open_emulator, nullptr) << name;
  }
  EXPECT_EQ(board_for_emulator("nope"), nullptr);
}

TEST(BoardTable, EmulateServesTheFirstEmulatorOfEachBoardInTableOrder) {
  std::string choices;
  for (const Board* b : all_boards()) {
    ASSERT_FALSE(b->emulators.empty()) << b->key;
    EXPECT_NE(b->serve, nullptr) << b->key;
    choices += std::string(choices.empty() ? "" : ",") + std::string(b->emulators[0]);
  }
  EXPECT_EQ(choices, "xarm,lsc6,raspblock");
}

TEST(BoardTable, StorageComesWhole) {
  for (const Board* b : all_boards()) {
    if (b->plan == nullptr) {
      EXPECT_EQ(b->upload, nullptr) << b->key;
      continue;
    }
    EXPECT_NE(b->upload, nullptr) << b->key;
    EXPECT_NE(b->acknowledge, nullptr) << b->key;
    EXPECT_NE(b->comment, nullptr) << b->key;
    EXPECT_NE(b->run_frame, nullptr) << b->key;
    EXPECT_NE(b->confirm_run, nullptr) << b->key;
    EXPECT_NE(b->stop_frame, nullptr) << b->key;
    EXPECT_FALSE(b->unconfirmed_run.empty()) << b->key;
    EXPECT_FALSE(b->run_name.empty()) << b->key;
  }
}

TEST(BoardTable, EveryBoardPlaysLive) {
  for (const Board* b : all_boards()) {
    EXPECT_NE(b->live_frames, nullptr) << b->key;
    EXPECT_NE(b->render, nullptr) << b->key;
    // A board nothing answers says so before it plays.
    if (b->probe == nullptr && b->style == LiveStyle::Moves) {
      EXPECT_FALSE(b->unprobed_note.empty()) << b->key;
    }
  }
}

TEST(BoardTable, DeviceCommandsFindTheirBoard) {
  EXPECT_EQ(board_for_device("", "").key, "xarm");  // the first discoverable board
  EXPECT_EQ(board_for_device("", "/dev/ttyUSB0").key, "xarm");
  EXPECT_EQ(board_for_device("lsc-6", "").key, "lsc6");
  EXPECT_EQ(board_for_device("", "emu:lsc6").key, "lsc6");
  EXPECT_EQ(board_for_device("", "emu:lsc6?baud=0").key, "lsc6");
  EXPECT_EQ(board_for_device("xarm", "emu:lsc6").key, "lsc6");  // the port says what is there
  EXPECT_EQ(board_for_device("lsc-6", "emu:xarm-hid").key, "xarm");
  EXPECT_EQ(board_for_device("nope", "").key, "xarm");
}

TEST(BoardTable, FamiliesShareCommandsAndPorts) {
  EXPECT_TRUE(same_family(*find_board("xarm"), *find_board("lsc6")));
  EXPECT_FALSE(same_family(*find_board("xarm"), *find_board("raspblock")));
  EXPECT_FALSE(same_family(*find_board("lsc6"), *find_board("raspblock")));
}

TEST(BoardTable, RowFacts) {
  const Board& xarm = *find_board("xarm");
  const Board& lsc6 = *find_board("lsc6");
  const Board& car = *find_board("raspblock");
  EXPECT_EQ(xarm.baud, 9600u);
  EXPECT_EQ(lsc6.baud, 9600u);
  EXPECT_EQ(car.baud, 115200u);
  EXPECT_TRUE(xarm.over_hid);
  EXPECT_FALSE(lsc6.over_hid);
  EXPECT_FALSE(car.over_hid);
  EXPECT_TRUE(xarm.discoverable);
  EXPECT_TRUE(lsc6.discoverable);
  EXPECT_FALSE(car.discoverable);
  EXPECT_TRUE(xarm.queries);
  EXPECT_FALSE(lsc6.queries);
  EXPECT_FALSE(lsc6.erases_one_group);
  EXPECT_EQ(car.plan, nullptr);
  EXPECT_NE(car.safe_stop, nullptr);
  EXPECT_EQ(car.style, LiveStyle::Stream);
}

TEST(BoardTable, RunAndStopFrames) {
  // docs/protocol/servo-controller.md: GroupRun 55 55 05 06 G timesLo timesHi, GroupStop 55 55 02
  // 07.
  EXPECT_EQ(to_hex(find_board("xarm")->run_frame(2, 1)), "55 55 05 06 02 01 00");
  EXPECT_EQ(to_hex(find_board("xarm")->stop_frame()), "55 55 02 07");
  // docs/protocol/lsc-6.md: Run 55 55 05 06 G cntLo cntHi, Stop 55 55 02 07.
  EXPECT_EQ(to_hex(find_board("lsc6")->run_frame(3, 0x0102)), "55 55 05 06 03 02 01");
  EXPECT_EQ(to_hex(find_board("lsc6")->stop_frame()), "55 55 02 07");
}

TEST(BoardTable, DeviceCommandsReachAServoControllerAndNothingElse) {
  // A profile or emulator of the servo-controller family is taken as given ...
  EXPECT_EQ(board_for_command("lsc-6", "").key, "lsc6");
  EXPECT_EQ(board_for_command("", "emu:lsc6").key, "lsc6");
  EXPECT_EQ(board_for_command("xarm", "emu:lsc6?seed=3").key, "lsc6");
  EXPECT_EQ(board_for_command("lsc-6", "emu:xarm").key, "xarm");
  // ... one of another family is not: the command talks to the board discovery finds.
  EXPECT_EQ(board_for_command("raspblock", "").key, "xarm");
  EXPECT_EQ(board_for_command("", "emu:raspblock").key, "xarm");
  EXPECT_EQ(board_for_command("", "").key, "xarm");
}

TEST(BoardTable, EmulatorsRefuseTheOptionsTheirBoardsCannotUse) {
  const Board& xarm = *find_board("xarm");
  const Board& lsc6 = *find_board("lsc6");
  const Board& car = *find_board("raspblock");
  const unsigned all = kFaults | kSeed | kDumpGroups | kPositions;
  EXPECT_EQ(refused_emulator_option(xarm, all).option, 0u);
  EXPECT_EQ(refused_emulator_option(lsc6, kFaults | kSeed | kDumpGroups).option, 0u);
  EXPECT_EQ(refused_emulator_option(lsc6, kPositions).option, kPositions);
  EXPECT_EQ(refused_emulator_option(lsc6, kPositions).reason, "");
  // Faults come first, and the seed goes with them.
  EXPECT_EQ(refused_emulator_option(car, all).option, kFaults);
  EXPECT_EQ(refused_emulator_option(car, kSeed).option, kSeed);
  EXPECT_EQ(refused_emulator_option(car, kSeed).reason, "the Raspblock board never replies");
  EXPECT_EQ(refused_emulator_option(car, kDumpGroups | kPositions).option, kDumpGroups);
  EXPECT_EQ(refused_emulator_option(car, kDumpGroups).reason,
            "the Raspblock board stores no groups");
  EXPECT_EQ(refused_emulator_option(car, 0).option, 0u);
}

TEST(BoardTable, EmulatorListsFollowTheTable) {
  EXPECT_EQ(served_emulators(), (std::vector<std::string_view>{"xarm", "lsc6", "raspblock"}));
  EXPECT_EQ(family_emulators(*find_board("lsc6")), (std::vector<std::string_view>{"xarm", "lsc6"}));
  EXPECT_EQ(family_emulators(*find_board("raspblock")),
            (std::vector<std::string_view>{"raspblock"}));
}

TEST(BoardTable, PosesReadBackAreNamedByTheBoardsOwnProfile) {
  EXPECT_EQ(find_board("xarm")->pose_profile, "xarm");
  EXPECT_EQ(find_board("lsc6")->pose_profile, "lsc-6");
}

// A file for one servo controller meeting the other: the board that answered, and the
// profiles whose files it runs.
TEST(BoardTable, TheOtherDialectOfAFamily) {
  const OtherDialect for_xarm = other_dialect(*find_board("xarm"));
  ASSERT_NE(for_xarm.answered, nullptr);
  EXPECT_EQ(for_xarm.answered->key, "lsc6");
  EXPECT_EQ(for_xarm.profiles, (std::vector<std::string>{"lsc-6", "learm"}));
  const OtherDialect for_lsc6 = other_dialect(*find_board("lsc6"));
  ASSERT_NE(for_lsc6.answered, nullptr);
  EXPECT_EQ(for_lsc6.answered->key, "xarm");
  EXPECT_EQ(for_lsc6.profiles, (std::vector<std::string>{"xarm", "bus", "lsc-16", "lsc-32"}));
  EXPECT_EQ(other_dialect(*find_board("raspblock")).answered, nullptr);  // nothing else stores
}

}  // namespace
}  // namespace seqc::boards
