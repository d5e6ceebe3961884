// The device commands' session (boards::XarmSession, runtime/boards/xarm_session.hpp) over a
// scripted link, and the words the CLI gives its failures (runtime/cli/board_text.hpp): the
// confirmation after unanswered commands, stale replies, notifications and failures.
// Reply bytes are written by hand from docs/protocol/servo-controller.md.
#include <gtest/gtest.h>

#include <deque>
#include <map>

#include "runtime/boards/xarm_session.hpp"
#include "runtime/cli/board_text.hpp"
#include "runtime/io/clock.hpp"
#include "base/bytes.hpp"
#include "runtime/upload/controller_link.hpp"

namespace seqc::cli {
namespace {

using std::chrono::milliseconds;

Bytes hex(std::string_view text) { return *parse_hex(text); }

// Answers the n-th write (1-based) with scripted bytes; silence otherwise. Bytes queued with
// `pending` are there before anything is written (a stale reply).
class ScriptedPort final : public io::Transport {
 public:
  explicit ScriptedPort(io::ManualClock& clock) : clock_(clock) {}
  std::map<int, Bytes> answers;
  Bytes pending;
  std::vector<Bytes> written;

  Status write(ByteView bytes) override {
    written.emplace_back(bytes.begin(), bytes.end());
    auto it = answers.find(static_cast<int>(written.size()));
    if (it != answers.end()) pending.insert(pending.end(), it->second.begin(), it->second.end());
    return Ok{};
  }
  io::ReadResult read(std::span<std::uint8_t> buffer, io::TimePoint deadline) override {
    if (pending.empty()) {
      clock_.sleep_until(deadline);
      return {io::ReadStatus::Timeout, 0, {}};
    }
    const std::size_t n = std::min(buffer.size(), pending.size());
    std::copy_n(pending.begin(), n, buffer.begin());
    pending.erase(pending.begin(), pending.begin() + static_cast<std::ptrdiff_t>(n));
    return {io::ReadStatus::Data, n, {}};
  }
  void discard_input() override { pending.clear(); }
  std::string describe() const override { return "scripted"; }

 private:
  io::ManualClock& clock_;
};

struct Fixture {
  io::ManualClock clock;
  ScriptedPort port{clock};
  upload::ControllerLink link{port, clock};
  boards::XarmSession session{link, milliseconds(200)};
};

// The session's first failure as the device commands say it.
std::optional<BoardError> error(const boards::XarmSession& s) {
  if (!s.failure()) return std::nullopt;
  return outcome_text(*s.failure(), "scripted", s.timeout(), "the controller");
}

TEST(DeviceSession, TellConfirmsWithABatteryCheck) {
  Fixture f;
  f.port.answers[2] = hex("55 55 04 0f 4c 1d");
  EXPECT_TRUE(f.session.tell(lsc::GroupStop{}));
  ASSERT_EQ(f.port.written.size(), 2u);
  EXPECT_EQ(to_hex(f.port.written[0]), "55 55 02 07");
  EXPECT_EQ(to_hex(f.port.written[1]), "55 55 02 0f");
  EXPECT_FALSE(error(f.session));
}

TEST(DeviceSession, ASecondCheckIsSentWhenTheFirstGoesUnanswered) {
  Fixture f;
  f.port.answers[3] = hex("55 55 04 0f 4c 1d");  // only the second check is answered
  EXPECT_TRUE(f.session.tell(lsc::GroupStop{}));
  EXPECT_EQ(f.port.written.size(), 3u);
  EXPECT_EQ(f.clock.now(), milliseconds(200));
}

TEST(DeviceSession, NotificationsAreKeptAndStaleRepliesAreNotTaken) {
  Fixture f;
  // A battery reply left over from before, then the group-started notification and the real
  // answer to this check (7.6 V = 0x1db0).
  f.port.pending = hex("55 55 04 0f 11 11");
  f.port.answers[2] = hex("55 55 05 06 03 02 00  55 55 04 0f b0 1d");
  EXPECT_TRUE(f.session.tell(lsc::GroupRun{3, 2}));
  ASSERT_EQ(f.session.notifications().size(), 1u);
  EXPECT_EQ(f.session.notifications()[0], lsc::Reply(lsc::GroupStarted{3, 2}));

  f.port.answers[3] = hex("55 55 04 0f b0 1d");
  f.port.pending = hex("55 55 04 0f 11 11");  // stale again
  auto v = f.session.ask<lsc::BatteryVoltage>(lsc::GetBatteryVoltage{}, "the battery voltage");
  ASSERT_TRUE(v);
  EXPECT_EQ(v->millivolts, 7600);
}

TEST(DeviceSession, NoReplyFailsAndLaterCallsDoNothing) {
  Fixture f;
  auto v = f.session.ask<lsc::ServoPositions>(lsc::ServoPositionRead{{1}}, "the positions");
  EXPECT_FALSE(v);
  ASSERT_TRUE(error(f.session));
  EXPECT_EQ(error(f.session)->code, ExitCode::DeviceFailure);
  EXPECT_EQ(error(f.session)->message,
            "no reply from the controller on scripted within 200 ms (waiting for the "
            "positions); check that the controller is powered and connected, and --port");
  EXPECT_FALSE(f.session.tell(lsc::GroupStop{}));
  EXPECT_EQ(f.port.written.size(), 1u);
}

TEST(DeviceSession, InterruptIsItsOwnFailure) {
  io::ManualClock clock;
  ScriptedPort port{clock};
  std::atomic<bool> interrupted{true};
  upload::ControllerLink link{port, clock, &interrupted};
  boards::XarmSession session{link, milliseconds(200)};
  EXPECT_FALSE(session.tell(lsc::GroupStop{}));
  ASSERT_TRUE(error(session));
  EXPECT_EQ(error(session)->code, ExitCode::Interrupted);
  EXPECT_TRUE(port.written.empty());
}

}  // namespace
}  // namespace seqc::cli
