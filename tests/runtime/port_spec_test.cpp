// Every --port form of docs/ports.md, and the mistakes people make with them.
#include <gtest/gtest.h>

#include "runtime/transport/port_spec.hpp"

namespace seqc::transport {
namespace {

PortSpec parsed(std::string_view text) {
  auto r = parse_port(text);
  if (!r) ADD_FAILURE() << text << ": " << r.error().message;
  return r ? *r : PortSpec{};
}

std::string error_of(std::string_view text) {
  auto r = parse_port(text);
  if (r) ADD_FAILURE() << text << " parsed";
  return r ? "" : r.error().message;
}

TEST(ParsePort, SpecsHoldWhatTheFactoriesSay) {
  PortSpec s = serial_port("/dev/ttyUSB0", 57600);
  EXPECT_EQ(s.kind, PortKind::Serial);
  EXPECT_EQ(s.path, "/dev/ttyUSB0");
  EXPECT_EQ(s.baud, 57600u);
  PortSpec h = hid_port("/dev/hidraw1");
  EXPECT_EQ(h.kind, PortKind::Hid);
  EXPECT_EQ(h.path, "/dev/hidraw1");
  EXPECT_FALSE(h.baud);
  PortSpec e = emulator_port("raspblock", "seed=1");
  EXPECT_EQ(e.kind, PortKind::Emulator);
  EXPECT_EQ(e.emulator, "raspblock");
  EXPECT_EQ(e.emulator_options, "seed=1");
  EXPECT_TRUE(e.path.empty());
}

TEST(ParsePort, SerialPaths) {
  EXPECT_EQ(parsed("/dev/ttyUSB0"), serial_port("/dev/ttyUSB0"));
  EXPECT_EQ(parsed("/dev/ttyUSB0@115200"), serial_port("/dev/ttyUSB0", 115200));
  EXPECT_EQ(parsed("serial:/dev/x"), serial_port("/dev/x"));
  EXPECT_EQ(parsed("serial:/dev/ttyAMA0@115200"), serial_port("/dev/ttyAMA0", 115200));
  EXPECT_EQ(parsed("ttyACM0"), serial_port("/dev/ttyACM0"));
  EXPECT_EQ(parsed("./dev/link"), serial_port("./dev/link"));
  // by-path names contain ':' after the first '/': still a path.
  EXPECT_EQ(parsed("/dev/serial/by-path/pci-0000:00:14.0-usb-0:1:1.0-port0@9600"),
            serial_port("/dev/serial/by-path/pci-0000:00:14.0-usb-0:1:1.0-port0", 9600));
}

TEST(ParsePort, PseudoTerminals) {
  EXPECT_EQ(parsed("pty:/dev/pts/3"), serial_port("/dev/pts/3"));
  EXPECT_EQ(parsed("/dev/pts/3"), serial_port("/dev/pts/3"));
  EXPECT_EQ(parsed("pty:/dev/pts/12@115200"), serial_port("/dev/pts/12", 115200));
}

TEST(ParsePort, Hid) {
  EXPECT_EQ(parsed("hid"), hid_port());
  EXPECT_EQ(parsed("hid:/dev/hidraw3"), hid_port("/dev/hidraw3"));
  // hidapi paths are opaque: kept whole, '@' included.
  EXPECT_EQ(parsed("hid:1-2:1.0@x"), hid_port("1-2:1.0@x"));
}

TEST(ParsePort, Emulators) {
  EXPECT_EQ(parsed("emu:xarm"), emulator_port("xarm"));
  EXPECT_EQ(parsed("emu:raspblock"), emulator_port("raspblock"));
  EXPECT_EQ(parsed("emu:xarm?drop=0.1&seed=7"), emulator_port("xarm", "drop=0.1&seed=7"));
  EXPECT_EQ(parsed("emu:xarm?"), emulator_port("xarm"));
}

TEST(ParsePort, Errors) {
  EXPECT_EQ(error_of(""),
            "invalid port '': expected a device path (/dev/ttyUSB0[@BAUD]), serial:PATH[@BAUD], "
            "pty:PATH[@BAUD], hid, hid:PATH, emu:xarm, emu:xarm-hid, emu:lsc6 or "
            "emu:raspblock");
  EXPECT_EQ(error_of("/dev/ttyUSB0@fast"),
            "invalid port '/dev/ttyUSB0@fast': 'fast' is not a baud rate (e.g. @115200)");
  EXPECT_EQ(error_of("/dev/ttyUSB0@"),
            "invalid port '/dev/ttyUSB0@': '' is not a baud rate (e.g. @115200)");
  EXPECT_EQ(error_of("/dev/ttyUSB0@-9600"),
            "invalid port '/dev/ttyUSB0@-9600': '-9600' is not a baud rate (e.g. @115200)");
  EXPECT_EQ(error_of("/dev/ttyUSB0@99999999999"),
            "invalid port '/dev/ttyUSB0@99999999999': '99999999999' is not a baud rate "
            "(e.g. @115200)");
  EXPECT_EQ(error_of("/dev/ttyUSB0@12345")
                .rfind("invalid port '/dev/ttyUSB0@12345': unsupported baud rate 12345; supported: "
                       "300, 600, 1200",
                       0),
            0u);
  EXPECT_EQ(error_of("serial:"), "invalid port 'serial:': the device path is missing");
  EXPECT_EQ(error_of("serial:@9600"), "invalid port 'serial:@9600': the device path is missing");
  EXPECT_EQ(error_of("hid:"),
            "invalid port 'hid:': the HID path is missing (e.g. hid:/dev/hidraw3)");
  EXPECT_EQ(error_of("emu:"),
            "invalid port 'emu:': the emulator name is missing; use emu:xarm, emu:xarm-hid, "
            "emu:lsc6 or emu:raspblock");
  EXPECT_EQ(error_of("emu:lsc16?x"),
            "invalid port 'emu:lsc16?x': unknown emulator 'lsc16'; use emu:xarm, emu:xarm-hid, "
            "emu:lsc6 or emu:raspblock");
  EXPECT_EQ(error_of("usb:/dev/ttyUSB0")
                .rfind("invalid port 'usb:/dev/ttyUSB0': unknown port "
                       "kind 'usb:'; expected a device path",
                       0),
            0u);
}

TEST(FormatPort, RoundTrips) {
  for (std::string_view text : {"/dev/ttyUSB0", "/dev/ttyUSB0@115200", "hid", "hid:/dev/hidraw3",
                                "emu:xarm", "emu:raspblock?seed=3", "/dev/pts/4@9600"}) {
    auto spec = parsed(text);
    EXPECT_EQ(format_port(spec), text);
    EXPECT_EQ(parsed(format_port(spec)), spec);
  }
  EXPECT_EQ(format_port(parsed("serial:/dev/x@57600")), "/dev/x@57600");
}

}  // namespace
}  // namespace seqc::transport
