// The emulator's USB HID face (emu:xarm-hid): HidTransport over EmulatedHidBackend, with the
// report bytes written by hand from docs/protocol/servo-controller.md ("Framing").
#include <gtest/gtest.h>

#include <array>

#include "runtime/emulator/hid_face.hpp"
#include "runtime/transport/open_port.hpp"
#include "tests/emulator/emu_test_util.hpp"

namespace seqc::emu::test {
namespace {

// 00 (report id), the frame, zeros to 64 data bytes.
Bytes report_of(const char* frame_hex, std::size_t size) {
  Bytes r = hex(frame_hex);
  r.resize(size, 0x00);
  return r;
}

TEST(HidFace, DiscoveredAndFramedAsTheController) {
  XArmEmulator emu;
  io::ManualClock clock;
  EmulatedHidBackend backend(emu, clock);
  auto link = transport::open_port(transport::hid_port(), clock, 9600, backend);
  ASSERT_TRUE(link.ok()) << link.error().message;
  EXPECT_EQ((*link)->describe(), "hid:emu:xarm-hid (0483:5750 LOBOT)");
  ASSERT_TRUE((*link)->write(hex("55 55 02 0f")).ok());
  ASSERT_NE(backend.last_opened(), nullptr);
  ASSERT_EQ(backend.last_opened()->reports_written().size(), 1u);
  EXPECT_EQ(hex_of(backend.last_opened()->reports_written()[0]),
            hex_of(report_of("00 55 55 02 0f", 65)));
  std::array<std::uint8_t, 16> buf{};
  const io::ReadResult r = (*link)->read(buf, clock.now() + 100ms);
  ASSERT_EQ(r.status, io::ReadStatus::Data);
  EXPECT_EQ(hex_of(Bytes(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(r.count))),
            "55 55 04 0f 4c 1d");
  ASSERT_EQ(backend.last_opened()->reports_read().size(), 1u);
  EXPECT_EQ(hex_of(backend.last_opened()->reports_read()[0]),
            hex_of(report_of("55 55 04 0f 4c 1d", 64)));
}

TEST(HidFace, ReportsGoOutOnePerMillisecond) {
  XArmEmulator emu;
  io::ManualClock clock;
  EmulatedHidBackend backend(emu, clock);
  auto device = backend.open(kEmulatedHidPath);
  ASSERT_TRUE(device.ok());
  const Bytes battery = report_of("00 55 55 02 0f", 65);
  ASSERT_TRUE((*device)->write(battery).ok());
  ASSERT_TRUE((*device)->write(battery).ok());
  EXPECT_EQ(emu.received().at(0).at, io::TimePoint{1ms});
  EXPECT_EQ(emu.received().at(1).at, io::TimePoint{2ms});
}

TEST(HidFace, RefusesWhatIsNotAnOutputReport) {
  XArmEmulator emu;
  io::ManualClock clock;
  EmulatedHidBackend backend(emu, clock);
  auto device = backend.open(kEmulatedHidPath);
  ASSERT_TRUE(device.ok());
  EXPECT_FALSE((*device)->write(hex("55 55 02 0f")).ok()) << "a bare frame";
  EXPECT_FALSE((*device)->write(report_of("01 55 55 02 0f", 65)).ok()) << "report id 1";
  EXPECT_TRUE(emu.received().empty());
  EXPECT_FALSE(backend.open("/dev/hidraw0").ok());
}

TEST(HidFace, AFrameTooBigForAReportIsRefusedByTheTransport) {
  XArmEmulator emu;
  io::ManualClock clock;
  EmulatedHidBackend backend(emu, clock);
  auto link = transport::open_port(transport::hid_port(), clock, 9600, backend);
  ASSERT_TRUE(link.ok());
  EXPECT_EQ((*link)->max_frame_bytes(), 64u);
  Bytes big = hex("55 55 43 03");  // LEN 0x43: 65 data bytes, 69 in all
  big.resize(69, 0x01);
  EXPECT_FALSE((*link)->write(big).ok());
  EXPECT_TRUE(backend.last_opened()->reports_written().empty());
}

}  // namespace
}  // namespace seqc::emu::test
