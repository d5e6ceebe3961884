// The --trace decorator: every byte both ways, timestamped on the link's clock.
#include <gtest/gtest.h>

#include <chrono>
#include <sstream>

#include "runtime/upload/trace_transport.hpp"

namespace seqc::upload {
namespace {

using namespace std::chrono_literals;

class Echo final : public io::Transport {
 public:
  explicit Echo(io::ManualClock& clock) : clock_(clock) {}
  Status write(ByteView bytes) override {
    pending.assign(bytes.begin(), bytes.end());
    return Ok{};
  }
  io::ReadResult read(std::span<std::uint8_t> buffer, io::TimePoint deadline) override {
    if (gone) return {io::ReadStatus::HangUp, 0, "gone"};
    if (pending.empty()) {
      clock_.sleep_until(deadline);
      return {io::ReadStatus::Timeout, 0, ""};
    }
    clock_.advance(1234us);
    std::copy(pending.begin(), pending.end(), buffer.begin());
    const std::size_t n = pending.size();
    pending.clear();
    return {io::ReadStatus::Data, n, ""};
  }
  void discard_input() override {}
  std::string describe() const override { return "echo"; }
  Bytes pending;
  bool gone = false;

 private:
  io::ManualClock& clock_;
};

TEST(TraceTransport, WritesEveryByteBothWaysWithTimes) {
  io::ManualClock clock(5s);
  Echo echo(clock);
  std::ostringstream out;
  TraceTransport trace(echo, clock, out);
  std::array<std::uint8_t, 16> buf{};
  ASSERT_TRUE(trace.write(Bytes{0x55, 0x55, 0x02, 0x0f}).ok());
  EXPECT_EQ(trace.read(buf, clock.now() + 1s).count, 4u);
  EXPECT_EQ(trace.read(buf, clock.now() + 1s).status, io::ReadStatus::Timeout);
  trace.discard_input();
  echo.gone = true;
  EXPECT_EQ(trace.read(buf, clock.now() + 1s).status, io::ReadStatus::HangUp);
  EXPECT_EQ(out.str(),
            "# seqc trace of echo; t in seconds, > to the device, < from it\n"
            "t=0.000000 > 55 55 02 0f\n"
            "t=0.001234 < 55 55 02 0f\n"
            "t=1.001234 # discarded pending input\n"
            "t=1.001234 < hang-up\n");
  EXPECT_EQ(trace.describe(), "echo");
}

}  // namespace
}  // namespace seqc::upload
