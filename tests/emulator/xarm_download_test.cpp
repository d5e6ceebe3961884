// The GroupDownload step 1-5 handshake as the emulated controller enforces it.
#include <gtest/gtest.h>

#include "tests/emulator/emu_test_util.hpp"

namespace seqc::emu::test {
namespace {

std::vector<lsc::GroupAction> actions(std::size_t n) {
  std::vector<lsc::GroupAction> out;
  for (std::size_t k = 0; k < n; ++k) out.push_back(test_action(k));
  return out;
}

TEST(XArmDownload, FullThousandTwentyActionsStoredExactly) {
  XArmEmulator emu;
  io::TimePoint t{0};
  const auto want = actions(1020);
  ASSERT_TRUE(download(emu, 7, want, t));
  auto stored = emu.stored_group(7);
  ASSERT_TRUE(stored.has_value());
  ASSERT_EQ(stored->size(), 1020u);
  EXPECT_EQ(*stored, want);
  EXPECT_FALSE(emu.downloading_group().has_value());
  // 1 + 4 + 1 + 1020 + 1 frames, none dropped.
  EXPECT_EQ(emu.received().size(), 1027u);
  for (const auto& r : emu.received()) EXPECT_FALSE(r.dropped_busy || r.dropped_fault);
  // Erase (60 ms) and 1,020 flash writes (2 ms each) took emulated time.
  EXPECT_EQ(t, at_ms(60 + 2 * 1020));
}

TEST(XArmDownload, HandWrittenOneActionDownloadBytes) {
  XArmEmulator emu;
  io::TimePoint t{0};
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 05 05 01 02 01"), t)), "55 55 04 05 01 00");
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 07 05 02 02 00 01 00"), t)), "55 55 04 05 02 00");
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 06 05 03 02 00 00"), t)), "55 55 04 05 03 00");
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 0c 05 04 02 00 00 0b e8 03 01 20 03"), t)),
            "55 55 04 05 04 00");
  EXPECT_FALSE(emu.stored_group(2).has_value()) << "valid only after step 5";
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 04 05 05 02"), t)), "55 55 04 05 05 00");
  auto stored = emu.stored_group(2);
  ASSERT_TRUE(stored.has_value());
  ASSERT_EQ(stored->size(), 1u);
  EXPECT_EQ((*stored)[0].time_ms, 1000);
  EXPECT_EQ((*stored)[0].servos, (std::vector<lsc::ServoTarget>{{1, 800}}));
}

// Sends the frames of a 300-action download up to (not including) `upto`.
void send_prefix(XArmEmulator& emu, std::uint8_t group, std::size_t upto, io::TimePoint& t) {
  const auto frames = download_frames(group, actions(300));
  for (std::size_t i = 0; i < upto; ++i) ASSERT_EQ(exchange(emu, frames[i], t), ack(frames[i][4]));
}

TEST(XArmDownload, OutOfOrderActionRefused) {
  XArmEmulator emu;
  io::TimePoint t{0};
  send_prefix(emu, 3, 4 + 2, t);  // open, 2 sizes, blocks, actions 0 and 1
  const auto a = test_action(3);
  // Index 3 when index 2 is due: refused.
  EXPECT_EQ(exchange(emu, action_frame(3, 0, 3, a), t), ack(4, 1));
  // Block 1 before block 0 is complete: refused.
  EXPECT_EQ(exchange(emu, action_frame(3, 1, 0, a), t), ack(4, 1));
  // Index 0 again (not the frame just stored): refused.
  EXPECT_EQ(exchange(emu, action_frame(3, 0, 0, test_action(0)), t), ack(4, 1));
  // The frame just stored, repeated exactly: re-acknowledged (a safe retry)...
  EXPECT_EQ(exchange(emu, action_frame(3, 0, 1, test_action(1)), t), ack(4, 0));
  // ...but the same slot with other contents is refused.
  EXPECT_EQ(exchange(emu, action_frame(3, 0, 1, test_action(9)), t), ack(4, 1));
  // Another group, a wrong marker, a wrong length: refused.
  EXPECT_EQ(exchange(emu, action_frame(4, 0, 2, test_action(2)), t), ack(4, 1));
  Bytes bad_marker = action_frame(3, 0, 2, test_action(2));
  bad_marker[8] = 0x0c;
  EXPECT_EQ(exchange(emu, bad_marker, t), ack(4, 1));
  EXPECT_EQ(exchange(emu, frame(0x05, {0x04, 3, 0, 2, 0x0b, 0x14, 0x00, 0x01, 0xf4}), t),
            ack(4, 1));
  // The refusals changed nothing: the due action is still accepted.
  EXPECT_EQ(exchange(emu, action_frame(3, 0, 2, test_action(2)), t), ack(4, 0));
}

TEST(XArmDownload, WrongCountsAndOrderRefused) {
  XArmEmulator emu;
  io::TimePoint t{0};
  // Steps 2-5 without a step 1: refused.
  EXPECT_EQ(exchange(emu, hex("55 55 07 05 02 01 00 05 00"), t), ack(2, 1));
  EXPECT_EQ(exchange(emu, hex("55 55 04 05 05 01"), t), ack(5, 1));
  // Open group 1 with 255 + 45 actions.
  EXPECT_EQ(exchange(emu, hex("55 55 06 05 01 01 ff 2d"), t), ack(1));
  // Step 2 count differing from step 1, and block 1 before block 0: refused.
  EXPECT_EQ(exchange(emu, hex("55 55 07 05 02 01 00 fe 00"), t), ack(2, 1));
  EXPECT_EQ(exchange(emu, hex("55 55 07 05 02 01 01 2d 00"), t), ack(2, 1));
  // Step 3 before every step 2: refused.
  EXPECT_EQ(exchange(emu, hex("55 55 07 05 03 01 00 00 01"), t), ack(3, 1));
  EXPECT_EQ(exchange(emu, hex("55 55 07 05 02 01 00 ff 00"), t), ack(2));
  // A repeat of the step 2 just accepted is re-acknowledged.
  EXPECT_EQ(exchange(emu, hex("55 55 07 05 02 01 00 ff 00"), t), ack(2));
  EXPECT_EQ(exchange(emu, hex("55 55 07 05 02 01 01 2d 00"), t), ack(2));
  // Step 3 listing one block where two were announced: refused.
  EXPECT_EQ(exchange(emu, hex("55 55 06 05 03 01 00 00"), t), ack(3, 1));
  // Step 4 before step 3: refused. Then the right list is accepted.
  EXPECT_EQ(exchange(emu, action_frame(1, 0, 0, test_action(0)), t), ack(4, 1));
  EXPECT_EQ(exchange(emu, hex("55 55 07 05 03 01 00 00 01"), t), ack(3));
  // Step 5 before every action arrived: refused, and the group stays empty.
  EXPECT_EQ(exchange(emu, hex("55 55 04 05 05 01"), t), ack(5, 1));
  EXPECT_FALSE(emu.stored_group(1).has_value());
  // Step 1 with a zero count or five blocks: refused.
  EXPECT_EQ(exchange(emu, hex("55 55 05 05 01 02 00"), t), ack(1, 1));
  EXPECT_EQ(exchange(emu, hex("55 55 09 05 01 02 ff ff ff ff 01"), t), ack(1, 1));
  // A step byte outside 1..5 names no step: ignored, no reply.
  EXPECT_EQ(exchange(emu, hex("55 55 04 05 06 01"), t), Bytes{});
}

TEST(XArmDownload, InterruptedDownloadLeavesGroupEmptyAndErasesOldOne) {
  XArmEmulator emu;
  io::TimePoint t{0};
  ASSERT_TRUE(download(emu, 5, actions(10), t));
  ASSERT_TRUE(emu.stored_group(5).has_value());
  // A new download of group 5 stops after three actions.
  const auto frames = download_frames(5, actions(20));
  for (std::size_t i = 0; i < 3 + 3; ++i) ASSERT_EQ(exchange(emu, frames[i], t), ack(frames[i][4]));
  EXPECT_FALSE(emu.stored_group(5).has_value()) << "step 1 erased the old group";
  // The host gives up and starts on another group: group 5 stays empty.
  ASSERT_TRUE(download(emu, 6, actions(2), t));
  EXPECT_FALSE(emu.stored_group(5).has_value());
  EXPECT_TRUE(emu.stored_group(6).has_value());
  // A GroupRun of the empty group does nothing and answers nothing.
  EXPECT_EQ(exchange(emu, hex("55 55 05 06 05 01 00"), t), Bytes{});
}

TEST(XArmDownload, PowerCycleAbandonsDownloadButKeepsStoredGroups) {
  XArmEmulator emu;
  io::TimePoint t{0};
  ASSERT_TRUE(download(emu, 1, actions(4), t));
  const auto frames = download_frames(2, actions(4));
  for (std::size_t i = 0; i < 5; ++i) ASSERT_EQ(exchange(emu, frames[i], t), ack(frames[i][4]));
  emu.power_cycle(t);
  EXPECT_FALSE(emu.downloading_group().has_value());
  for (std::size_t i = 5; i < frames.size(); ++i) {
    EXPECT_EQ(exchange(emu, frames[i], t), ack(frames[i][4], 1));
  }
  EXPECT_FALSE(emu.stored_group(2).has_value());
  EXPECT_EQ(emu.stored_group(1)->size(), 4u);
}

TEST(XArmDownload, FrameArrivingWhileBusyIsDroppedSilently) {
  XArmEmulator emu;  // flash_erase_time 60 ms, flash_write_time 2 ms
  const auto frames = download_frames(0, actions(2));
  emu.receive(frames[0], at_ms(0));   // step 1: busy erasing until 60 ms
  emu.receive(frames[1], at_ms(30));  // dropped
  ASSERT_EQ(emu.received().size(), 2u);
  EXPECT_FALSE(emu.received()[0].dropped_busy);
  EXPECT_TRUE(emu.received()[1].dropped_busy);
  EXPECT_EQ(emu.received()[1].raw, frames[1]);
  EXPECT_EQ(emu.next_output_at(), at_ms(60)) << "the step 1 ack comes after the erase";
  EXPECT_EQ(emu.take_output(at_ms(60)), ack(1));
  EXPECT_EQ(emu.next_output_at(), std::nullopt) << "no reply for the dropped frame";
  // Two frames in one write: the second arrives while the first is being processed.
  Bytes both = frames[1];
  both.insert(both.end(), frames[2].begin(), frames[2].end());
  io::TimePoint t = at_ms(60);
  // Step 2 takes no time (command_time 0), so both are handled.
  EXPECT_EQ(exchange(emu, both, t),
            Bytes({0x55, 0x55, 0x04, 0x05, 0x02, 0x00, 0x55, 0x55, 0x04, 0x05, 0x03, 0x00}));
  // Two actions back to back: the second lands inside the first's 2 ms flash write.
  Bytes two = frames[3];
  two.insert(two.end(), frames[4].begin(), frames[4].end());
  EXPECT_EQ(exchange(emu, two, t), ack(4));
  EXPECT_TRUE(emu.received().back().dropped_busy);
}

TEST(XArmDownload, CommandTimeMakesOrdinaryFramesBusy) {
  XArmConfig config;
  config.command_time = 5ms;
  XArmEmulator emu(config);
  emu.receive(hex("55 55 02 0f 55 55 02 0f"), at_ms(0));
  emu.receive(hex("55 55 02 0f"), at_ms(5));
  ASSERT_EQ(emu.received().size(), 3u);
  EXPECT_FALSE(emu.received()[0].dropped_busy);
  EXPECT_TRUE(emu.received()[1].dropped_busy);
  EXPECT_FALSE(emu.received()[2].dropped_busy);
  EXPECT_EQ(emu.next_output_at(), at_ms(5));
  EXPECT_EQ(hex_of(emu.take_output(at_ms(10))), "55 55 04 0f 4c 1d 55 55 04 0f 4c 1d");
}

}  // namespace
}  // namespace seqc::emu::test
