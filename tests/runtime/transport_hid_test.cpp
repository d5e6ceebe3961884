// HidTransport over a fake hidapi device: report layout, padding, LEN stripping, draining,
// deadlines. Expected reports are written out by hand from the document's "Report Data" table.
#include <gtest/gtest.h>

#include "runtime/io/clock.hpp"
#include "runtime/transport/hid_transport.hpp"
#include "runtime/transport/open_port.hpp"
#include "tests/runtime/fake_hid.hpp"

namespace seqc::transport {
namespace {

using namespace std::chrono_literals;
using testing::FakeHidBackend;
using testing::FakeHidDevice;
using testing::FakeHidState;
using testing::lobot;

// Another gadget on ST's generic custom-HID id.
HidDeviceInfo st_generic(std::string path) {
  HidDeviceInfo info = lobot(std::move(path));
  info.product = "STM32 Custom HID";
  info.manufacturer = "STMicroelectronics";
  return info;
}

Bytes padded(Bytes head, std::size_t size) {
  head.resize(size, 0x00);
  return head;
}

struct HidFixture : ::testing::Test {
  std::shared_ptr<FakeHidState> state = std::make_shared<FakeHidState>();
  io::ManualClock clock;
  HidTransport t{std::make_unique<FakeHidDevice>(state), clock,
                 "hid:/dev/hidraw3 (0483:5750 LOBOT)"};

  io::ReadResult read(Bytes& out, std::size_t max, io::TimePoint deadline) {
    Bytes buf(max);
    auto r = t.read(buf, deadline);
    out.assign(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(r.count));
    return r;
  }
};

TEST_F(HidFixture, WritesOneReportWithIdZeroAndZeroPadding) {
  // GetBatteryVoltage: 55 55 02 0F.
  ASSERT_TRUE(t.write(Bytes{0x55, 0x55, 0x02, 0x0f}).ok());
  ASSERT_EQ(state->written.size(), 1u);
  const Bytes expected = padded({0x00, 0x55, 0x55, 0x02, 0x0f}, 65);
  EXPECT_EQ(state->written[0], expected);
}

TEST_F(HidFixture, WritesTheVendorServoMoveExample) {
  // Move servo 1 to 2000 in 1000 ms (vendor document).
  ASSERT_TRUE(t.write(Bytes{0x55, 0x55, 0x08, 0x03, 0x01, 0xe8, 0x03, 0x01, 0xd0, 0x07}).ok());
  ASSERT_EQ(state->written.size(), 1u);
  EXPECT_EQ(state->written[0],
            padded({0x00, 0x55, 0x55, 0x08, 0x03, 0x01, 0xe8, 0x03, 0x01, 0xd0, 0x07}, 65));
}

TEST_F(HidFixture, AFrameFillingTheReportHasNoPadding) {
  Bytes frame{0x55, 0x55, 62, 0x04};  // 60 data bytes: 64 bytes in all
  for (std::uint8_t i = 1; i <= 60; ++i) frame.push_back(i);
  ASSERT_TRUE(t.write(frame).ok());
  ASSERT_EQ(state->written.size(), 1u);
  ASSERT_EQ(state->written[0].size(), 65u);
  EXPECT_EQ(state->written[0][0], 0x00);
  EXPECT_EQ(Bytes(state->written[0].begin() + 1, state->written[0].end()), frame);
}

TEST_F(HidFixture, RefusesWhatIsNotExactlyOneFittingFrame) {
  Bytes two{0x55, 0x55, 0x02, 0x0f, 0x55, 0x55, 0x02, 0x0f};
  EXPECT_FALSE(t.write(two).ok());
  EXPECT_FALSE(t.write(Bytes{0x55, 0x55, 0x04}).ok());
  EXPECT_FALSE(t.write(Bytes{0x01, 0x02, 0x03, 0x04}).ok());
  Bytes too_big{0x55, 0x55, 63, 0x04};  // 61 data bytes: 65 bytes, one more than a report holds
  too_big.resize(65, 0x01);
  auto r = t.write(too_big);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("64-byte HID report"), std::string::npos) << r.error().message;
  EXPECT_TRUE(state->written.empty());
}

TEST_F(HidFixture, WriteFailuresCarryHidapiText) {
  state->write_error = "hid_write: Broken pipe";
  auto r = t.write(Bytes{0x55, 0x55, 0x02, 0x0f});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().message,
            "cannot write to hid:/dev/hidraw3 (0483:5750 LOBOT): hid_write: Broken pipe");
}

TEST_F(HidFixture, ReadStripsPaddingByLen) {
  // Battery reply 7500 mV, then padding; the 0xee bytes past LEN are not part of the frame.
  state->reports.push_back(padded({0x55, 0x55, 0x04, 0x0f, 0x4c, 0x1d, 0xee, 0xee}, 64));
  Bytes got;
  auto r = read(got, 256, clock.now() + 100ms);
  ASSERT_EQ(r.status, io::ReadStatus::Data);
  EXPECT_EQ(got, (Bytes{0x55, 0x55, 0x04, 0x0f, 0x4c, 0x1d}));
}

TEST_F(HidFixture, ASmallBufferGetsTheFrameInPieces) {
  state->reports.push_back(padded({0x55, 0x55, 0x05, 0x06, 0x01, 0x02, 0x00}, 64));
  state->reports.push_back(padded({0x55, 0x55, 0x02, 0x07}, 64));
  // Each read hands out what is left of the current report before fetching the next one.
  std::vector<Bytes> pieces;
  Bytes part;
  for (int i = 0; i < 5; ++i) {
    ASSERT_EQ(read(part, 3, clock.now() + 100ms).status, io::ReadStatus::Data);
    pieces.push_back(part);
  }
  EXPECT_EQ(pieces,
            (std::vector<Bytes>{
                {0x55, 0x55, 0x05}, {0x06, 0x01, 0x02}, {0x00}, {0x55, 0x55, 0x02}, {0x07}}));
  EXPECT_EQ(read(part, 3, clock.now() + 100ms).status, io::ReadStatus::Timeout);
}

TEST_F(HidFixture, UndecodableReportsArePassedOnWithoutPadding) {
  state->reports.push_back(padded({0x12, 0x34, 0x55}, 64));
  Bytes got;
  ASSERT_EQ(read(got, 256, clock.now() + 100ms).status, io::ReadStatus::Data);
  EXPECT_EQ(got, (Bytes{0x12, 0x34, 0x55}));
}

TEST_F(HidFixture, TimeoutUsesTheRemainingTimeRoundedUp) {
  clock.advance(5s);
  Bytes got;
  EXPECT_EQ(read(got, 64, clock.now() + 250ms).status, io::ReadStatus::Timeout);
  EXPECT_EQ(read(got, 64, clock.now() + 1500us).status, io::ReadStatus::Timeout);
  EXPECT_EQ(read(got, 64, clock.now() - 1s).status, io::ReadStatus::Timeout);
  EXPECT_EQ(state->read_timeouts, (std::vector<int>{250, 2, 0}));
}

TEST_F(HidFixture, UnplugIsAHangUpAndOtherErrorsKeepTheirText) {
  state->script.push_back({HidRead::State::Gone, 0, "hid_read_timeout: device disconnected"});
  state->script.push_back({HidRead::State::Error, 0, "hid_read_timeout: Input/output error"});
  Bytes got;
  auto gone = read(got, 64, clock.now() + 1s);
  EXPECT_EQ(gone.status, io::ReadStatus::HangUp);
  EXPECT_NE(gone.message.find("device disconnected"), std::string::npos) << gone.message;
  auto err = read(got, 64, clock.now() + 1s);
  EXPECT_EQ(err.status, io::ReadStatus::Error);
  EXPECT_EQ(err.message,
            "cannot read from hid:/dev/hidraw3 (0483:5750 LOBOT): "
            "hid_read_timeout: Input/output error");
}

TEST_F(HidFixture, DiscardDrainsQueuedReportsWithoutWaiting) {
  state->reports.push_back(padded({0x55, 0x55, 0x05, 0x06, 0x01, 0x02, 0x00}, 64));
  state->reports.push_back(padded({0x55, 0x55, 0x02, 0x07}, 64));
  state->reports.push_back(padded({0x55, 0x55, 0x05, 0x08, 0x01, 0x02, 0x00}, 64));
  // Leave half a frame pending as well.
  Bytes got;
  ASSERT_EQ(read(got, 2, clock.now() + 1s).status, io::ReadStatus::Data);
  state->read_timeouts.clear();
  t.discard_input();
  EXPECT_TRUE(state->reports.empty());
  // Two stale reports and the read that found the queue empty, none of them waiting.
  EXPECT_EQ(state->read_timeouts, (std::vector<int>{0, 0, 0}));
  EXPECT_EQ(read(got, 64, clock.now() + 10ms).status, io::ReadStatus::Timeout);
}

TEST_F(HidFixture, DiscardGivesUpOnADeviceThatNeverStops) {
  state->endless = true;
  t.discard_input();
  EXPECT_EQ(state->read_timeouts.size(),
            static_cast<std::size_t>(HidTransport::kMaxDrainedReports));
}

TEST_F(HidFixture, DescribeAndPacing) {
  EXPECT_EQ(t.describe(), "hid:/dev/hidraw3 (0483:5750 LOBOT)");
  EXPECT_EQ(t.seconds_per_byte(), 0.0);
}

TEST(OpenHidPort, OpensTheOneLobotDevice) {
  FakeHidBackend hid;
  hid.devices = {lobot("/dev/hidraw3"), st_generic("/dev/hidraw1")};
  io::ManualClock clock;
  auto t = open_port(hid_port(), clock, 9600, hid);
  ASSERT_TRUE(t) << t.error().message;
  EXPECT_EQ((*t)->describe(), "hid:/dev/hidraw3 (0483:5750 LOBOT)");
  EXPECT_EQ(hid.opened, std::vector<std::string>{"/dev/hidraw3"});
  ASSERT_TRUE((*t)->write(Bytes{0x55, 0x55, 0x02, 0x0f}).ok());
  EXPECT_EQ(hid.state->written.at(0).size(), 65u);
}

TEST(OpenHidPort, NoneOrSeveralLobotDevicesIsAnError) {
  FakeHidBackend hid;
  io::ManualClock clock;
  hid.devices = {st_generic("/dev/hidraw1")};
  auto none = open_port(hid_port(), clock, 9600, hid);
  ASSERT_FALSE(none);
  EXPECT_EQ(none.error().message.rfind("no xArm controller found over USB HID", 0), 0u)
      << none.error().message;

  hid.devices = {lobot("/dev/hidraw5"), lobot("/dev/hidraw2")};
  auto several = open_port(hid_port(), clock, 9600, hid);
  ASSERT_FALSE(several);
  EXPECT_EQ(several.error().message,
            "several xArm controllers found over USB HID; choose one with --port:\n"
            "  hid:/dev/hidraw2\n"
            "  hid:/dev/hidraw5");
  EXPECT_TRUE(hid.opened.empty());
}

TEST(OpenHidPort, AnExplicitPathIsOpenedAsGivenAndErrorsPassThrough) {
  FakeHidBackend hid;
  io::ManualClock clock;
  auto t = open_port(hid_port("/dev/hidraw7"), clock, 9600, hid);
  ASSERT_TRUE(t) << t.error().message;
  EXPECT_EQ(hid.opened, std::vector<std::string>{"/dev/hidraw7"});

  hid.open_errors["/dev/hidraw8"] = "permission denied opening /dev/hidraw8";
  auto denied = open_port(hid_port("/dev/hidraw8"), clock, 9600, hid);
  ASSERT_FALSE(denied);
  EXPECT_EQ(denied.error().message, "permission denied opening /dev/hidraw8");
}

// Reconnecting after an unplug (Transport::reopen): the controller is looked for every 50 ms
// of the test clock until the deadline.
struct HidReopen : ::testing::Test {
  FakeHidBackend hid;
  io::ManualClock clock;
  std::unique_ptr<io::Transport> t;
  io::TimePoint unplugged{0};

  void open_and_unplug(HidDeviceInfo device) {
    hid.devices = {std::move(device)};
    auto opened = open_port(hid_port(), clock, 9600, hid);
    ASSERT_TRUE(opened) << opened.error().message;
    t = std::move(*opened);
    hid.state->script.push_back({HidRead::State::Gone, 0, "No such device"});
    Bytes buf(8);
    ASSERT_EQ(t->read(buf, clock.now() + 100ms).status, io::ReadStatus::HangUp);
    hid.devices.clear();
    unplugged = clock.now();
  }
  // From `after` past the unplug on, the backend lists `device`.
  void plug_in(HidDeviceInfo device, io::Duration after) {
    hid.before_enumerate = [this, device, after](FakeHidBackend& b) {
      if (clock.now() >= unplugged + after) b.devices = {device};
    };
  }
};

TEST_F(HidReopen, TheSameControllerIsFoundUnderItsNewNodeAndUsedAgain) {
  open_and_unplug(lobot("/dev/hidraw3", "0001A"));
  plug_in(lobot("/dev/hidraw4", "0001A"), 2s);
  ASSERT_TRUE(t->reopen(unplugged + 10s));
  EXPECT_EQ(clock.now(), unplugged + 2s);
  EXPECT_EQ(hid.opened, (std::vector<std::string>{"/dev/hidraw3", "/dev/hidraw4"}));
  EXPECT_EQ(t->describe(), "hid:/dev/hidraw4 (0483:5750 LOBOT)");
  // Both ways work again: GetBatteryVoltage out, its reply 55 55 04 0F 4C 1D in.
  ASSERT_TRUE(t->write(Bytes{0x55, 0x55, 0x02, 0x0f}).ok());
  EXPECT_EQ(hid.state->written.back(), padded({0x00, 0x55, 0x55, 0x02, 0x0f}, 65));
  hid.state->reports.push_back(padded({0x55, 0x55, 0x04, 0x0f, 0x4c, 0x1d}, 64));
  Bytes buf(16);
  const io::ReadResult r = t->read(buf, clock.now() + 100ms);
  ASSERT_EQ(r.status, io::ReadStatus::Data);
  EXPECT_EQ(Bytes(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(r.count)),
            (Bytes{0x55, 0x55, 0x04, 0x0f, 0x4c, 0x1d}));
}

TEST_F(HidReopen, AnotherControllerIsNotTakenForItAndTheWaitEndsAtTheDeadline) {
  open_and_unplug(lobot("/dev/hidraw3", "0001A"));
  plug_in(lobot("/dev/hidraw3", "0002B"), 1s);
  EXPECT_FALSE(t->reopen(unplugged + 5s));
  EXPECT_EQ(clock.now(), unplugged + 5s);
  EXPECT_EQ(hid.opened, std::vector<std::string>{"/dev/hidraw3"});
}

TEST_F(HidReopen, WithoutASerialNumberTheControllerIsKnownByItsPath) {
  open_and_unplug(lobot("/dev/hidraw3"));
  plug_in(lobot("/dev/hidraw4"), 1s);
  EXPECT_FALSE(t->reopen(unplugged + 3s));
  EXPECT_EQ(hid.opened, std::vector<std::string>{"/dev/hidraw3"});

  plug_in(lobot("/dev/hidraw3"), 4s);
  ASSERT_TRUE(t->reopen(unplugged + 10s));
  EXPECT_EQ(clock.now(), unplugged + 4s);
  EXPECT_EQ(hid.opened, (std::vector<std::string>{"/dev/hidraw3", "/dev/hidraw3"}));
}

TEST(OpenPort, EmulatorSpecsAreTheCallersJob) {
  FakeHidBackend hid;
  io::ManualClock clock;
  auto t = open_port(emulator_port("xarm"), clock, 9600, hid);
  ASSERT_FALSE(t);
  EXPECT_NE(t.error().message.find("emu:xarm"), std::string::npos);
}

}  // namespace
}  // namespace seqc::transport
