// plan_frames(): every download frame encoded once and labelled once. The bytes and labels are
// written out here by hand from the GroupDownload table and docs/protocol/lsc-6.md.
#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "protocol/planned_frame.hpp"

namespace seqc {
namespace {

TEST(PlannedFrame, GroupDownloadStepsAreEncodedAndLabelled) {
  const std::vector<lsc::Request> steps = {
      lsc::GroupDownloadOpen{1, {2}},
      lsc::GroupDownloadSize{1, 0, 2},
      lsc::GroupDownloadBlocks{1, 1},
      lsc::GroupDownloadAction{1, 0, 0, 1000, {{1, 1000}}},
      lsc::GroupDownloadAction{1, 0, 1, 500, {{2, 300}}},
      lsc::GroupDownloadClose{1},
  };
  auto plan = plan_frames(steps);
  ASSERT_TRUE(plan.ok()) << plan.error().message;
  ASSERT_EQ(plan->size(), 6u);

  const std::vector<std::string> bytes = {
      "55 55 05 05 01 01 02",
      "55 55 07 05 02 01 00 02 00",
      "55 55 06 05 03 01 00 00",
      "55 55 0c 05 04 01 00 00 0b e8 03 01 e8 03",
      "55 55 0c 05 04 01 00 01 0b f4 01 02 2c 01",
      "55 55 04 05 05 01",
  };
  const std::vector<std::string> what = {
      "step 1 (open group 1)",
      "step 2 (size of block 0)",
      "step 3 (block list)",
      "step 4 (action 1 of 2: block 0, index 0)",
      "step 4 (action 2 of 2: block 0, index 1)",
      "step 5 (close)",
  };
  const std::vector<std::string> short_what = {
      "step 1", "step 2", "step 3", "step 4 (action 1)", "step 4 (action 2)", "step 5"};
  const std::vector<std::string> fields = {
      "step 1 open | group 1 | block counts 2",
      "step 2 size | group 1 | block 0 | count 2 | pad 00",
      "step 3 blocks | group 1 | pad 00 | blocks used 1",
      "step 4 action | group 1 | block 0 | index 0 | marker 0b | time 1000 ms | servos 1",
      "step 4 action | group 1 | block 0 | index 1 | marker 0b | time 500 ms | servos 1",
      "step 5 close | group 1",
  };
  const std::vector<int> step = {1, 2, 3, 4, 4, 5};
  const std::vector<std::optional<std::size_t>> keyframe = {
      std::nullopt, std::nullopt, std::nullopt, 0u, 1u, std::nullopt};
  for (std::size_t i = 0; i < plan->size(); ++i) {
    const PlannedFrame& f = (*plan)[i];
    SCOPED_TRACE(i);
    EXPECT_EQ(to_hex(f.bytes), bytes[i]);
    EXPECT_EQ(f.index, i);
    EXPECT_EQ(f.step, step[i]);
    EXPECT_EQ(f.is_action, step[i] == 4);
    EXPECT_EQ(f.keyframe, keyframe[i]);
    EXPECT_EQ(f.what, what[i]);
    EXPECT_EQ(f.short_what, short_what[i]);
    EXPECT_EQ(f.fields, fields[i]);
    EXPECT_EQ(f.request, DialectRequest{steps[i]});
    EXPECT_EQ(f.dialect, &kXarmDialect);
  }
}

TEST(PlannedFrame, Lsc6ActionsAreEncodedAndLabelled) {
  const std::vector<lsc6::DownloadAction> actions = {
      lsc6::DownloadAction{1, 2, 0, 500, {{1, 1500}, {6, 2500}}},
      lsc6::DownloadAction{1, 2, 1, 100, {}},
  };
  auto plan = plan_frames(actions);
  ASSERT_TRUE(plan.ok()) << plan.error().message;
  ASSERT_EQ(plan->size(), 2u);

  const PlannedFrame& first = (*plan)[0];
  EXPECT_EQ(to_hex(first.bytes), "55 55 0e 19 01 02 00 02 f4 01 01 dc 05 06 c4 09");
  EXPECT_EQ(first.index, 0u);
  EXPECT_EQ(first.step, 0);
  EXPECT_TRUE(first.is_action);
  EXPECT_EQ(first.keyframe, std::optional<std::size_t>(0));
  EXPECT_EQ(first.what, "action 1 of 2");
  EXPECT_EQ(first.short_what, "action 1");
  EXPECT_EQ(first.fields, "download action | group 1 | total 2 | index 0 | time 500 ms | servos 2");
  EXPECT_EQ(first.request, DialectRequest{lsc6::Request{actions[0]}});
  EXPECT_EQ(first.dialect, &kLsc6Dialect);
  EXPECT_TRUE(first.dialect->sniff(first.bytes));

  const PlannedFrame& pause = (*plan)[1];
  EXPECT_EQ(to_hex(pause.bytes), "55 55 08 19 01 02 01 00 64 00");
  EXPECT_EQ(pause.index, 1u);
  EXPECT_EQ(pause.keyframe, std::optional<std::size_t>(1));
  EXPECT_EQ(pause.what, "action 2 of 2");
  EXPECT_EQ(pause.short_what, "action 2");
  EXPECT_EQ(pause.fields, "download action | group 1 | total 2 | index 1 | time 100 ms | servos 0");
}

TEST(PlannedFrame, AFrameItsEncoderRefusesFailsThePlan) {
  // Channel 9 is not one of the LSC-6's outputs 1-6.
  const std::vector<lsc6::DownloadAction> actions = {
      lsc6::DownloadAction{0, 1, 0, 500, {{9, 1500}}},
  };
  EXPECT_FALSE(plan_frames(actions).ok());
}

TEST(PlannedFrame, AnEmptyPlanHasNoFrames) {
  auto xarm = plan_frames(std::vector<lsc::Request>{});
  ASSERT_TRUE(xarm.ok());
  EXPECT_TRUE(xarm->empty());
  auto lsc6 = plan_frames(std::vector<lsc6::DownloadAction>{});
  ASSERT_TRUE(lsc6.ok());
  EXPECT_TRUE(lsc6->empty());
}

}  // namespace
}  // namespace seqc
