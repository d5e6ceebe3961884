// Faults: parsing the spec, and every fault reproducible from its seed.
#include <gtest/gtest.h>

#include <string>

#include "tests/emulator/emu_test_util.hpp"

namespace seqc::emu::test {
namespace {

TEST(XArmFaultSpec, ParsesEveryKey) {
  auto f = parse_faults(
      "drop=0.01,corrupt=0.02,late=0.03,late-by=250ms,dup=0.04,silent-after=100,hangup-at=500,"
      "seed=7");
  ASSERT_TRUE(f.ok()) << f.error().message;
  EXPECT_EQ(f->drop, 0.01);
  EXPECT_EQ(f->corrupt, 0.02);
  EXPECT_EQ(f->late_ack, 0.03);
  EXPECT_EQ(f->late_by, 250ms);
  EXPECT_EQ(f->duplicate_ack, 0.04);
  EXPECT_EQ(f->silent_after, std::optional<std::size_t>(100));
  EXPECT_EQ(f->hangup_at, std::optional<std::size_t>(500));
  EXPECT_EQ(f->seed, 7u);
  EXPECT_EQ(describe_faults(*f),
            "drop=0.01,corrupt=0.02,late=0.03,late-by=250ms,dup=0.04,silent-after=100,"
            "hangup-at=500,seed=7");
  EXPECT_EQ(parse_faults("late-by=2s")->late_by, 2s);
  EXPECT_EQ(parse_faults("late-by=150")->late_by, 150ms);
  EXPECT_FALSE(parse_faults("")->any());
  EXPECT_EQ(describe_faults(*parse_faults("")), "none");
}

TEST(XArmFaultSpec, RejectsMistakes) {
  EXPECT_EQ(parse_faults("dorp=0.1").error().message,
            "unknown fault 'dorp'; did you mean 'drop'? (known: seed, drop, corrupt, late, "
            "late-by, dup, silent-after, hangup-at, back-after, reset, reset-at, boot-time, "
            "busy, busy-for, frame-gap, split, clock)");
  EXPECT_EQ(parse_faults("drop=1.5").error().message, "fault 'drop': rate 1.5 is outside 0..1");
  EXPECT_EQ(parse_faults("drop").error().message, "fault 'drop' needs a value (key=value)");
  EXPECT_EQ(parse_faults("late-by=soon").error().message,
            "fault 'late-by': 'soon' is not a duration (e.g. 400ms, 2s)");
  EXPECT_EQ(parse_faults("seed=-1").error().message,
            "fault 'seed': '-1' is not a non-negative integer");
  EXPECT_FALSE(parse_faults("hangup-at=0").ok());
}

struct FaultRun {
  std::string received;  // raw hex and flags of every received piece
  Bytes output;
  std::string timed_output;  // when each piece of output was taken
  std::size_t replies = 0;   // battery replies seen intact
};

// The host sends `n` battery requests 50 ms apart and collects everything sent back.
FaultRun run(const std::string& spec, std::size_t n = 200) {
  XArmConfig config;
  auto faults = parse_faults(spec);
  EXPECT_TRUE(faults.ok());
  config.faults = *faults;
  XArmEmulator emu(config);
  FaultRun r;
  for (std::size_t i = 0; i < n; ++i) {
    const io::TimePoint t = at_ms(static_cast<std::int64_t>(50 * i));
    emu.receive(hex("55 55 02 0f"), t);
    while (auto next = emu.next_output_at()) {
      if (*next > t + 49ms) break;
      Bytes got = emu.take_output(*next);
      r.timed_output += std::to_string(next->count()) + ": " + to_hex(got) + "\n";
      r.output.insert(r.output.end(), got.begin(), got.end());
    }
  }
  Bytes rest = emu.take_output(at_ms(50 * static_cast<std::int64_t>(n) + 10000));
  r.output.insert(r.output.end(), rest.begin(), rest.end());
  for (const auto& f : emu.received()) {
    r.received += to_hex(f.raw) + (f.dropped_fault ? " F" : "") + (f.dropped_busy ? " B" : "") +
                  (f.frame ? " ok" : " -") + "\n";
  }
  const Bytes want = hex("55 55 04 0f 4c 1d");
  for (std::size_t i = 0; i + want.size() <= r.output.size(); ++i) {
    if (std::equal(want.begin(), want.end(), r.output.begin() + static_cast<std::ptrdiff_t>(i))) {
      ++r.replies;
    }
  }
  return r;
}

void expect_deterministic(const std::string& spec, const std::string& other_seed_spec) {
  const FaultRun a = run(spec);
  const FaultRun b = run(spec);
  EXPECT_EQ(a.received, b.received) << spec;
  EXPECT_EQ(a.timed_output, b.timed_output) << spec;
  const FaultRun c = run(other_seed_spec);
  EXPECT_TRUE(a.received != c.received || a.timed_output != c.timed_output)
      << "seed changes the faults: " << spec << " vs " << other_seed_spec;
}

TEST(XArmFaults, DropLosesFramesWithoutReply) {
  expect_deterministic("drop=0.3,seed=11", "drop=0.3,seed=12");
  const FaultRun r = run("drop=0.3,seed=11");
  std::size_t dropped = 0;
  for (std::size_t p = r.received.find(" F"); p != std::string::npos;
       p = r.received.find(" F", p + 1)) {
    ++dropped;
  }
  EXPECT_GT(dropped, 30u);
  EXPECT_LT(dropped, 90u);
  EXPECT_EQ(r.replies, 200u - dropped) << "exactly the dropped frames go unanswered";
  EXPECT_EQ(run("drop=1").replies, 0u);
}

TEST(XArmFaults, CorruptFlipsOneByteOfARequestOrAReply) {
  expect_deterministic("corrupt=0.2,seed=3", "corrupt=0.2,seed=4");
  // Requests: with every frame corrupted, each recorded frame differs from 55 55 02 0f in
  // exactly one byte. A flip in 55 55 LEN leaves nothing the controller can frame; a flip of
  // the command byte (0f -> f0) is taken as it arrived, an unknown command. Nothing is answered.
  XArmConfig config;
  config.faults.corrupt = 1.0;
  XArmEmulator emu(config);
  for (int i = 0; i < 40; ++i) emu.receive(hex("55 55 02 0f"), at_ms(50 * i));
  EXPECT_EQ(emu.take_output(at_ms(5000)), Bytes{});
  ASSERT_EQ(emu.received().size(), 40u);
  int framing = 0, command = 0;
  for (const auto& f : emu.received()) {
    int diffs = 0;
    for (std::size_t i = 0; i < 4; ++i) diffs += f.raw[i] != hex("55 55 02 0f")[i];
    EXPECT_EQ(diffs, 1);
    if (f.raw[3] == 0xf0) {
      ++command;
      EXPECT_EQ(f.flipped_at, std::optional<std::size_t>(3));
      EXPECT_FALSE(f.dropped_fault);
      ASSERT_TRUE(f.frame.has_value());
      EXPECT_EQ(f.frame->cmd, 0xf0);
    } else {
      ++framing;
      EXPECT_EQ(f.flipped_at, std::nullopt);
      EXPECT_TRUE(f.dropped_fault);
      EXPECT_EQ(f.dropped, DropReason::FaultCorrupt);
      EXPECT_FALSE(f.frame.has_value());
    }
  }
  // A quarter of the bytes is the command byte: both kinds happen in 40 frames.
  EXPECT_GT(framing, 0);
  EXPECT_GT(command, 0);
  // Replies: the output has the same length as without faults, but some replies differ.
  const FaultRun r = run("corrupt=0.2,seed=3");
  const FaultRun clean = run("");
  EXPECT_LT(r.replies, 200u);
  EXPECT_EQ(clean.replies, 200u);
}

TEST(XArmFaults, TheFlippedByteIsTheDrawScaledByTheFrameLength) {
  // where in [0, 1) picks byte floor(where * size): each of a 4-byte frame's bytes a quarter.
  EXPECT_EQ(FaultInjector::flip_index(4, 0.0), 0u);
  EXPECT_EQ(FaultInjector::flip_index(4, 0.249), 0u);
  EXPECT_EQ(FaultInjector::flip_index(4, 0.25), 1u);
  EXPECT_EQ(FaultInjector::flip_index(4, 0.75), 3u);
  EXPECT_EQ(FaultInjector::flip_index(4, 0.9999), 3u);
  EXPECT_EQ(FaultInjector::flip_index(14, 0.65), 9u);  // 9.1
  Bytes frame = hex("55 55 02 0f");
  EXPECT_EQ(FaultInjector::flip(frame, 0.8), 3u);
  EXPECT_EQ(hex_of(frame), "55 55 02 f0");
}

// The protocol has no checksum: a byte of an action's time or position flipped on the wire is
// acknowledged like any other and stored as it arrived. Over many seeds, every such flip in the
// hand-written one-action download (time 1000 ms = e8 03, servo 1 at 800 = 20 03) ends with
// the flipped value stored, as if the host had sent it.
TEST(XArmFaults, AFlippedPositionByteIsAcknowledgedAndStored) {
  const std::vector<std::string> frames{
      "55 55 05 05 01 02 01", "55 55 07 05 02 02 00 01 00", "55 55 06 05 03 02 00 00",
      "55 55 0c 05 04 02 00 00 0b e8 03 01 20 03", "55 55 04 05 05 02"};
  int stored_flipped = 0;
  for (std::uint64_t seed = 1; seed <= 400; ++seed) {
    XArmConfig config;
    config.faults.corrupt = 0.2;
    config.faults.seed = seed;
    XArmEmulator emu(config);
    io::TimePoint t{0};
    std::vector<std::string> acks;
    for (const auto& f : frames) acks.push_back(hex_of(exchange(emu, hex(f), t)));
    ASSERT_EQ(emu.received().size(), 5u);
    const ReceivedFrame& step4 = emu.received()[3];
    // Bytes 9..13 are tLo tHi id posLo posHi.
    if (!step4.flipped_at || *step4.flipped_at < 9) continue;
    bool others_clean = true;
    for (std::size_t i : {0, 1, 2, 4})
      others_clean =
          others_clean && !emu.received()[i].flipped_at && !emu.received()[i].dropped_fault;
    if (!others_clean) continue;
    // The reply may carry a flip of its own; the group being stored shows step 4 was taken.
    const auto stored = emu.stored_group(2);
    ASSERT_TRUE(stored.has_value()) << "seed " << seed;
    ASSERT_EQ(stored->size(), 1u);
    const lsc::GroupAction& a = (*stored)[0];
    switch (*step4.flipped_at) {
      case 9:
        EXPECT_EQ(a.time_ms, 0x0317);
        break;  // e8 -> 17
      case 10:
        EXPECT_EQ(a.time_ms, 0xfce8);
        break;  // 03 -> fc
      case 11:
        EXPECT_EQ(a.servos, (std::vector<lsc::ServoTarget>{{0xfe, 800}}));
        break;
      case 12:
        EXPECT_EQ(a.servos, (std::vector<lsc::ServoTarget>{{1, 0x03df}}));
        break;
      case 13:
        EXPECT_EQ(a.servos, (std::vector<lsc::ServoTarget>{{1, 0xfc20}}));
        break;
      default:
        ADD_FAILURE() << "flipped byte " << *step4.flipped_at;
    }
    ++stored_flipped;
  }
  EXPECT_GT(stored_flipped, 0) << "no seed flipped only an action byte";
}

TEST(XArmFaults, LateReplyComesLateByLater) {
  expect_deterministic("late=0.5,seed=5", "late=0.5,seed=6");
  XArmConfig config;
  config.faults.late_ack = 1.0;
  config.faults.late_by = 400ms;
  XArmEmulator emu(config);
  emu.receive(hex("55 55 02 0f"), at_ms(10));
  EXPECT_EQ(emu.next_output_at(), at_ms(410));
  EXPECT_EQ(emu.take_output(at_ms(409)), Bytes{});
  EXPECT_EQ(hex_of(emu.take_output(at_ms(410))), "55 55 04 0f 4c 1d");
}

TEST(XArmFaults, DuplicateReplySentTwice) {
  expect_deterministic("dup=0.5,seed=8", "dup=0.5,seed=9");
  XArmConfig config;
  config.faults.duplicate_ack = 1.0;
  XArmEmulator emu(config);
  io::TimePoint t{0};
  EXPECT_EQ(hex_of(exchange(emu, hex("55 55 04 05 05 00"), t)),
            "55 55 04 05 05 01 55 55 04 05 05 01");
  EXPECT_EQ(run("dup=1").replies, 400u);
}

TEST(XArmFaults, SilentAfterStopsAnswering) {
  const FaultRun r = run("silent-after=3", 6);
  EXPECT_EQ(r.replies, 3u);
  EXPECT_EQ(r.received,
            "55 55 02 0f ok\n55 55 02 0f ok\n55 55 02 0f ok\n"
            "55 55 02 0f F -\n55 55 02 0f F -\n55 55 02 0f F -\n");
}

TEST(XArmFaults, HangupAtClosesTheLink) {
  XArmConfig config;
  config.faults.hangup_at = 2;
  XArmEmulator emu(config);
  emu.receive(hex("55 55 02 0f"), at_ms(0));
  EXPECT_FALSE(emu.hung_up());
  emu.receive(hex("55 55 02 0f 55 55 02 0f"), at_ms(0));
  EXPECT_TRUE(emu.hung_up());
  EXPECT_EQ(emu.take_output(at_ms(100)), Bytes{}) << "a closed link carries nothing";
  EXPECT_EQ(emu.next_output_at(), std::nullopt);
  emu.receive(hex("55 55 02 0f"), at_ms(200));
  ASSERT_EQ(emu.received().size(), 2u) << "the third frame never arrives";
  EXPECT_TRUE(emu.received()[1].dropped_fault);
  EXPECT_EQ(emu.frames_received(), 2u);
}

TEST(XArmFaults, SameSeedSameDownloadOutcome) {
  // A whole download under mixed faults is reproducible byte for byte.
  auto once = [] {
    XArmConfig config;
    config.faults = *parse_faults("drop=0.05,corrupt=0.05,late=0.05,dup=0.05,seed=21");
    XArmEmulator emu(config);
    io::TimePoint t{0};
    Bytes out;
    std::vector<lsc::GroupAction> actions;
    for (std::size_t k = 0; k < 300; ++k) actions.push_back(test_action(k));
    for (const Bytes& f : download_frames(4, actions)) {
      Bytes got = exchange(emu, f, t, 500ms);
      out.insert(out.end(), got.begin(), got.end());
      t += 1ms;
    }
    return std::make_pair(emu.received_bytes(), out);
  };
  EXPECT_EQ(once(), once());
}

}  // namespace
}  // namespace seqc::emu::test
