// Opening ports: every emulator a port names, with and without the test hooks, and every way
// opening can fail. Nothing here touches a real device: discovery sees a fake system.
#include <gtest/gtest.h>

#include <chrono>

#include "runtime/boards/ports.hpp"

namespace seqc::boards {
namespace {

using std::chrono::milliseconds;

// A system with no serial ports and no HID devices.
class EmptySystem final : public transport::DeviceLister {
 public:
  std::vector<std::string> list_directory(const std::string&) const override { return {}; }
  std::optional<std::string> resolve(const std::string&) const override { return std::nullopt; }
  Result<std::vector<transport::HidDeviceInfo>> lobot_hid_devices() const override {
    return std::vector<transport::HidDeviceInfo>{};
  }
};

const Board& board(std::string_view key) { return *find_board(key); }

// The controller answers a battery check through the opened port.
void expect_answers(OpenedPort& port) {
  ASSERT_NE(port.transport, nullptr);
  ASSERT_NE(port.clock, nullptr);
  const Outcome probed = board("xarm").probe(Line{*port.transport, *port.clock});
  EXPECT_TRUE(probed.ok()) << static_cast<int>(probed.failure);
}

TEST(BoardsOpenPort, EmuXarmMakesItsOwnController) {
  io::ManualClock host;
  OpenResult r = open_port({"emu:xarm", &board("xarm")}, host);
  ASSERT_TRUE(r.port.has_value());
  EXPECT_TRUE(r.port->emulated);
  EXPECT_EQ(r.port->board, &board("xarm"));
  EXPECT_NE(r.port->controller, nullptr);
  EXPECT_EQ(r.port->clock, r.port->emulated_clock.get());
  // Paced like the wire: 10 bits a byte at 9600 baud.
  EXPECT_DOUBLE_EQ(r.port->transport->seconds_per_byte(), 10.0 / 9600);
  expect_answers(*r.port);
  EXPECT_EQ(host.now(), io::TimePoint{});  // emulated time only
}

TEST(BoardsOpenPort, EmuXarmTakesTheOptionsOfItsEmulator) {
  io::ManualClock host;
  OpenResult r = open_port({"emu:xarm?baud=0", nullptr}, host);
  ASSERT_TRUE(r.port.has_value());
  EXPECT_EQ(r.port->transport->seconds_per_byte(), 0.0);
  EXPECT_EQ(r.port->board, &board("xarm"));
}

TEST(BoardsOpenPort, HooksReachTheCallersEmulators) {
  io::ManualClock host;
  io::ManualClock emulated;
  emu::XArmEmulator xarm{emu::XArmConfig{}};
  emu::Lsc6Emulator lsc6{emu::Lsc6Config{}};
  const Hooks hooks{&xarm, &lsc6, &emulated, nullptr};

  OpenResult a = open_port({"emu:xarm", &board("xarm")}, host, hooks);
  ASSERT_TRUE(a.port.has_value());
  EXPECT_EQ(a.port->controller, nullptr);
  EXPECT_EQ(a.port->clock, &emulated);
  expect_answers(*a.port);
  EXPECT_EQ(to_hex(xarm.received_bytes()), "55 55 02 0f");

  OpenResult b = open_port({"emu:lsc6", &board("lsc6")}, host, hooks);
  ASSERT_TRUE(b.port.has_value());
  EXPECT_EQ(b.port->controller, nullptr);
  EXPECT_EQ(b.port->clock, &emulated);
  EXPECT_EQ(b.port->board, &board("lsc6"));
  ASSERT_TRUE(b.port->transport->write(board("lsc6").stop_frame()));
  EXPECT_EQ(to_hex(lsc6.received_bytes()), "55 55 02 07");
}

TEST(BoardsOpenPort, HooksApplyOnlyWithTheirClock) {
  io::ManualClock host;
  emu::XArmEmulator xarm{emu::XArmConfig{}};
  OpenResult r = open_port({"emu:xarm", nullptr}, host, Hooks{&xarm, nullptr, nullptr, nullptr});
  ASSERT_TRUE(r.port.has_value());
  EXPECT_NE(r.port->controller, nullptr);
  expect_answers(*r.port);
  EXPECT_TRUE(xarm.received_bytes().empty());
}

TEST(BoardsOpenPort, EmuLsc6MakesItsOwnBoard) {
  io::ManualClock host;
  OpenResult r = open_port({"emu:lsc6", nullptr}, host);
  ASSERT_TRUE(r.port.has_value());
  EXPECT_EQ(r.port->board, &board("lsc6"));
  EXPECT_NE(r.port->controller, nullptr);
  EXPECT_EQ(r.port->clock, r.port->emulated_clock.get());
  // An xArm command may still be sent there: the family decides, not the dialect.
  EXPECT_TRUE(open_port({"emu:lsc6", &board("xarm")}, host).port.has_value());
}

TEST(BoardsOpenPort, EmuRaspblockStampsWithTheCallersClock) {
  io::ManualClock host;
  OpenResult r = open_port({"emu:raspblock", &board("raspblock")}, host);
  ASSERT_TRUE(r.port.has_value());
  EXPECT_EQ(r.port->board, &board("raspblock"));
  EXPECT_NE(r.port->raspblock, nullptr);
  EXPECT_EQ(r.port->clock, &host);
  EXPECT_EQ(r.port->transport->describe(), "emu:raspblock");
  ASSERT_TRUE(r.port->transport->write(board("raspblock").safe_stop()));
  EXPECT_EQ(r.port->raspblock->packets().size(), 1u);
}

TEST(BoardsOpenPort, WhatTheCarsEmulatorReceivedIsCounted) {
  io::ManualClock host;
  OpenResult r = open_port({"emu:raspblock", &board("raspblock")}, host);
  ASSERT_TRUE(r.port.has_value());
  ASSERT_TRUE(received(*r.port).has_value());
  EXPECT_EQ(received(*r.port)->packets, 0u);
  ASSERT_TRUE(r.port->transport->write(board("raspblock").safe_stop()));
  ASSERT_TRUE(r.port->transport->write(board("raspblock").safe_stop()));
  EXPECT_EQ(received(*r.port)->packets, 2u);
  EXPECT_EQ(received(*r.port)->rejected, 0u);
  // Other emulators count nothing this way.
  OpenResult x = open_port({"emu:xarm", &board("xarm")}, host);
  ASSERT_TRUE(x.port.has_value());
  EXPECT_FALSE(received(*x.port).has_value());
}

TEST(BoardsOpenPort, EmuXarmHidKeepsItsBackendAndCarriesOneReportAFrame) {
  io::ManualClock host;
  OpenResult r = open_port({"emu:xarm-hid", &board("xarm")}, host);
  ASSERT_TRUE(r.port.has_value()) << r.port.has_value();
  EXPECT_NE(r.port->hid_backend, nullptr);
  EXPECT_NE(r.port->controller, nullptr);
  EXPECT_GT(r.port->transport->max_frame_bytes(), 0u);
  expect_answers(*r.port);
}

TEST(BoardsOpenPort, MalformedPort) {
  io::ManualClock host;
  OpenResult r = open_port({"emu:nope", nullptr}, host);
  ASSERT_FALSE(r.port.has_value());
  EXPECT_EQ(r.failure.problem, PortProblem::Malformed);
  EXPECT_NE(r.failure.detail.find("emu:nope"), std::string::npos) << r.failure.detail;
}

TEST(BoardsOpenPort, BadEmulatorOptions) {
  io::ManualClock host;
  for (const char* port : {"emu:xarm?bogus=1", "emu:lsc6?bogus=1", "emu:xarm-hid?bogus=1"}) {
    OpenResult r = open_port({port, nullptr}, host);
    ASSERT_FALSE(r.port.has_value()) << port;
    EXPECT_EQ(r.failure.problem, PortProblem::EmulatorOptions) << port;
    EXPECT_FALSE(r.failure.detail.empty()) << port;
  }
}

TEST(BoardsOpenPort, AnEmulatorOfAnotherFamily) {
  io::ManualClock host;
  OpenResult a = open_port({"emu:xarm", &board("raspblock")}, host);
  ASSERT_FALSE(a.port.has_value());
  EXPECT_EQ(a.failure.problem, PortProblem::WrongEmulator);
  EXPECT_EQ(a.failure.reached, &board("xarm"));

  OpenResult b = open_port({"emu:raspblock", &board("xarm")}, host);
  ASSERT_FALSE(b.port.has_value());
  EXPECT_EQ(b.failure.problem, PortProblem::WrongEmulator);
  EXPECT_EQ(b.failure.reached, &board("raspblock"));

  // No board named: any servo controller.
  OpenResult c = open_port({"emu:raspblock", nullptr}, host);
  ASSERT_FALSE(c.port.has_value());
  EXPECT_EQ(c.failure.problem, PortProblem::WrongEmulator);
}

TEST(BoardsOpenPort, HidForABoardWithoutIt) {
  io::ManualClock host;
  OpenResult r = open_port({"hid", &board("raspblock")}, host);
  ASSERT_FALSE(r.port.has_value());
  EXPECT_EQ(r.failure.problem, PortProblem::WrongKind);
}

TEST(BoardsOpenPort, ABoardThatCannotBeFoundNeedsAPort) {
  io::ManualClock host;
  OpenResult r = open_port({"", &board("raspblock")}, host);
  ASSERT_FALSE(r.port.has_value());
  EXPECT_EQ(r.failure.problem, PortProblem::NeedsPort);
}

TEST(BoardsOpenPort, DiscoveryFindingNothing) {
  io::ManualClock host;
  const EmptySystem system;
  OpenResult r = open_port({"", &board("xarm")}, host, Hooks{nullptr, nullptr, nullptr, &system});
  ASSERT_FALSE(r.port.has_value());
  EXPECT_EQ(r.failure.problem, PortProblem::NotFound);
  EXPECT_EQ(r.failure.detail, transport::no_controller_message());
}

TEST(BoardsOpenPort, APortThatCannotBeOpened) {
  io::ManualClock host;
  OpenResult r = open_port({"/nonexistent/ttyUSB9", &board("xarm")}, host);
  ASSERT_FALSE(r.port.has_value());
  EXPECT_EQ(r.failure.problem, PortProblem::CannotOpen);
  EXPECT_NE(r.failure.detail.find("/nonexistent/ttyUSB9"), std::string::npos) << r.failure.detail;
}

}  // namespace
}  // namespace seqc::boards
