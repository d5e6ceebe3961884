// Discovery over a fake /dev and hidapi; choosing the default port; the `seqc ports` text.
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

#include <gtest/gtest.h>

#include "runtime/transport/port_discovery.hpp"
#include "runtime/transport/port_messages.hpp"
#include "tests/runtime/fake_hid.hpp"

namespace seqc::transport {
namespace {

using testing::lobot;

class FakeLister final : public DeviceLister {
 public:
  std::map<std::string, std::vector<std::string>> dirs;
  std::map<std::string, std::string> links;  // path -> target; missing = dangling
  std::vector<HidDeviceInfo> hid;
  std::string hid_error;

  std::vector<std::string> list_directory(const std::string& dir) const override {
    auto it = dirs.find(dir);
    return it == dirs.end() ? std::vector<std::string>{} : it->second;
  }
  std::optional<std::string> resolve(const std::string& path) const override {
    auto it = links.find(path);
    if (it == links.end()) return std::nullopt;
    return it->second;
  }
  Result<std::vector<HidDeviceInfo>> lobot_hid_devices() const override {
    if (!hid_error.empty()) return make_error(hid_error);
    return hid;
  }
  std::map<std::string, std::string> files;  // sysfs attributes
  std::optional<std::string> read_line(const std::string& path) const override {
    auto it = files.find(path);
    if (it == files.end()) return std::nullopt;
    return it->second;
  }
};

const char* const kCh340 = "/dev/serial/by-id/usb-1a86_USB_Serial-if00-port0";

TEST(DiscoverPorts, SerialByIdIsPreferredAndNotListedTwice) {
  FakeLister fs;
  fs.dirs["/dev/serial/by-id"] = {"usb-1a86_USB_Serial-if00-port0", "usb-gone-if00"};
  fs.links[kCh340] = "/dev/ttyUSB0";
  fs.dirs["/dev"] = {"null", "ttyS0", "ttyACM1", "ttyUSB0", "hidraw0", "tty", "ttyUSB1"};
  auto d = discover_ports(fs);
  EXPECT_TRUE(d.warnings.empty());
  std::vector<PortCandidate> expected{
      serial_candidate("/dev/serial/by-id/usb-1a86_USB_Serial-if00-port0", "/dev/ttyUSB0"),
      serial_candidate("/dev/ttyACM1", "/dev/ttyACM1"),
      serial_candidate("/dev/ttyUSB1", "/dev/ttyUSB1"),
  };
  EXPECT_EQ(d.candidates, expected);
}

// On-board UARTs are listed when the serial core reports hardware behind them (type != 0),
// after the USB ports, and never picked when --port is left out.
TEST(DiscoverPorts, OnboardUartsThatAnswerAreListedButNotChosen) {
  FakeLister fs;
  fs.dirs["/dev"] = {"ttyS0", "ttyS1", "ttyS2", "ttyAMA0", "ttyUSB0"};
  fs.files["/sys/class/tty/ttyS0/type"] = "4";     // a 16550A
  fs.files["/sys/class/tty/ttyS1/type"] = "0";     // PORT_UNKNOWN: nothing there
  fs.files["/sys/class/tty/ttyAMA0/type"] = "32";  // PL011 on a Raspberry Pi
  // ttyS2: no sysfs attribute at all (not a serial-core port): left out.
  const Discovery d = discover_ports(fs);
  ASSERT_EQ(d.candidates.size(), 3u);
  EXPECT_EQ(d.candidates[0].path, "/dev/ttyUSB0");
  EXPECT_FALSE(d.candidates[0].onboard_uart);
  EXPECT_EQ(d.candidates[1].path, "/dev/ttyAMA0");
  EXPECT_TRUE(d.candidates[1].onboard_uart);
  EXPECT_EQ(d.candidates[2].path, "/dev/ttyS0");
  EXPECT_EQ(format_port_list(d.candidates),
            "/dev/ttyUSB0\n/dev/ttyAMA0  on-board UART\n/dev/ttyS0  on-board UART\n");
  auto chosen = select_default_port(d.candidates);
  ASSERT_TRUE(chosen.ok());
  EXPECT_EQ(chosen->path, "/dev/ttyUSB0");
  // Only UARTs: nothing is chosen for the user.
  EXPECT_FALSE(select_default_port({d.candidates[1], d.candidates[2]}).ok());
}

TEST(FormatPortJson, OneObjectPerCandidate) {
  EXPECT_EQ(format_port_json({}), "[]\n");
  PortCandidate uart = serial_candidate("/dev/ttyAMA0", "/dev/ttyAMA0");
  uart.onboard_uart = true;
  EXPECT_EQ(format_port_json({serial_candidate(kCh340, "/dev/ttyUSB0"), uart,
                              hid_candidate(lobot("/dev/hidraw2", "2019-03"))}),
            "[\n"
            "  {\"port\": \"/dev/serial/by-id/usb-1a86_USB_Serial-if00-port0\", \"kind\": "
            "\"serial\", \"device\": \"/dev/ttyUSB0\"},\n"
            "  {\"port\": \"/dev/ttyAMA0\", \"kind\": \"uart\", \"device\": \"/dev/ttyAMA0\"},\n"
            "  {\"port\": \"hid:/dev/hidraw2\", \"kind\": \"hid\", \"device\": \"/dev/hidraw2\", "
            "\"product\": \"LOBOT\", \"manufacturer\": \"MyUSB_HID\", \"serial_number\": "
            "\"2019-03\"}\n"
            "]\n");
}

TEST(DiscoverPorts, HidDevicesFollowSerialOnes) {
  FakeLister fs;
  fs.dirs["/dev"] = {"ttyUSB0"};
  fs.hid = {lobot("/dev/hidraw2", "0001")};
  auto d = discover_ports(fs);
  ASSERT_EQ(d.candidates.size(), 2u);
  EXPECT_EQ(d.candidates[1].kind, PortKind::Hid);
  EXPECT_EQ(d.candidates[1].spec(), hid_port("/dev/hidraw2"));
  EXPECT_EQ(d.candidates[1].hid.serial_number, "0001");
}

TEST(DiscoverPorts, HidapiFailureIsAWarningNotTheEnd) {
  FakeLister fs;
  fs.dirs["/dev"] = {"ttyACM0"};
  fs.hid_error = "hid_init failed";
  auto d = discover_ports(fs);
  ASSERT_EQ(d.candidates.size(), 1u);
  EXPECT_EQ(d.warnings, std::vector<std::string>{"cannot list USB HID devices: hid_init failed"});
}

TEST(FindLobotDevices, MatchesVendorProductAndProductString) {
  testing::FakeHidBackend hid;
  HidDeviceInfo other_st = lobot("/dev/hidraw1");
  other_st.product = "STM32 Custom HID";
  HidDeviceInfo other_pid = lobot("/dev/hidraw4");
  other_pid.product_id = 0x5740;
  hid.devices = {lobot("/dev/hidraw9"), other_st, other_pid, lobot("/dev/hidraw3")};
  auto found = find_lobot_devices(hid);
  ASSERT_TRUE(found);
  ASSERT_EQ(found->size(), 2u);
  EXPECT_EQ((*found)[0].path, "/dev/hidraw3");
  EXPECT_EQ((*found)[1].path, "/dev/hidraw9");
}

TEST(SelectDefaultPort, ExactlyOneIsChosen) {
  PortCandidate only = serial_candidate(kCh340, "/dev/ttyUSB0");
  auto r = select_default_port({only});
  ASSERT_TRUE(r);
  EXPECT_EQ(*r, only);
  EXPECT_EQ(r->spec(), serial_port(kCh340));
}

TEST(SelectDefaultPort, NoneSaysWhereItLookedAndWhatToTry) {
  auto r = select_default_port({});
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().message,
            "no controller found (looked for /dev/serial/by-id/*, /dev/ttyUSB*, /dev/ttyACM* and "
            "USB HID 0483:5750 \"LOBOT\")\n"
            "  hint: plug the controller in and turn it on; `dmesg` shows the device it creates\n"
            "  hint: if a HID controller is plugged in but not listed, install the udev rule "
            "(docs/ports.md)\n"
            "  hint: a Raspblock board on a Raspberry Pi is on the UART: --port "
            "/dev/ttyAMA0@115200\n"
            "  hint: to try without hardware: --port emu:xarm");
}

TEST(SelectDefaultPort, SeveralAreListed) {
  auto r = select_default_port({
      serial_candidate(kCh340, "/dev/ttyUSB0"),
      hid_candidate(lobot("/dev/hidraw2")),
  });
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().message,
            "2 possible controllers found; choose one with --port:\n"
            "  /dev/serial/by-id/usb-1a86_USB_Serial-if00-port0 -> /dev/ttyUSB0\n"
            "  hid:/dev/hidraw2  LOBOT (MyUSB_HID)");
}

TEST(FormatPortList, OneLinePerCandidate) {
  EXPECT_EQ(format_port_list({
                serial_candidate(kCh340, "/dev/ttyUSB0"),
                serial_candidate("/dev/ttyACM0", "/dev/ttyACM0"),
                hid_candidate(lobot("/dev/hidraw2", "2019-03")),
            }),
            "/dev/serial/by-id/usb-1a86_USB_Serial-if00-port0 -> /dev/ttyUSB0\n"
            "/dev/ttyACM0\n"
            "hid:/dev/hidraw2  LOBOT (MyUSB_HID) serial 2019-03\n");
  EXPECT_EQ(format_port_list({}), "");
}

TEST(PortMessages, PermissionHints) {
  const std::string rule_hint =
      "  (or install seqc's udev rule, 70-seqc.rules, which gives the user at the machine\n"
      "  access to the usual USB serial adapters; see docs/ports.md)";
  EXPECT_EQ(permission_denied_message("/dev/ttyUSB0", std::string("dialout")),
            "permission denied opening /dev/ttyUSB0\n"
            "  hint: /dev/ttyUSB0 belongs to the 'dialout' group; add yourself to it, then log "
            "out and back in:\n"
            "    sudo usermod -aG dialout $USER\n" +
                rule_hint);
  // The group the node really has, not always dialout (Arch: uucp).
  EXPECT_EQ(permission_denied_message("/dev/ttyACM0", std::string("uucp")),
            "permission denied opening /dev/ttyACM0\n"
            "  hint: /dev/ttyACM0 belongs to the 'uucp' group; add yourself to it, then log out "
            "and back in:\n"
            "    sudo usermod -aG uucp $USER\n" +
                rule_hint);
  // root- or tty-owned nodes: the usual serial group is still the advice, not "belongs to root".
  const std::string root_owned = permission_denied_message("/dev/ttyUSB0", std::string("root"));
  EXPECT_NE(root_owned.find("serial ports usually belong to the 'dialout' group"),
            std::string::npos);
  EXPECT_EQ(root_owned.find("belongs to"), std::string::npos);
  EXPECT_NE(permission_denied_message("/dev/ttyUSB0", std::nullopt).find("dialout"),
            std::string::npos);
  EXPECT_EQ(permission_denied_message("/dev/hidraw3", std::string("root")),
            "permission denied opening /dev/hidraw3\n"
            "  hint: install seqc's udev rule so your login can use the controller (the .deb\n"
            "  installs it as /usr/lib/udev/rules.d/70-seqc.rules); from a source tree:\n"
            "    sudo cp scripts/udev/70-seqc.rules /etc/udev/rules.d/\n"
            "    sudo udevadm control --reload-rules && sudo udevadm trigger\n"
            "  then unplug and replug the controller (see docs/ports.md)");
}

TEST(PortMessages, ErrnoChoosesTheMessage) {
  EXPECT_EQ(describe_open_errno("/dev/ttyUSB0", EBUSY, std::nullopt),
            "/dev/ttyUSB0 is in use by another program (another seqc, a serial monitor or "
            "ModemManager); close it and try again");
  EXPECT_EQ(describe_open_errno("/dev/ttyUSB0", ENOENT, std::nullopt),
            "no such port /dev/ttyUSB0 (is the controller plugged in? `seqc ports` lists what is "
            "connected)");
  EXPECT_EQ(describe_open_errno("/dev/ttyUSB0", EACCES, std::string("dialout")),
            permission_denied_message("/dev/ttyUSB0", std::string("dialout")));
  EXPECT_EQ(describe_open_errno("/dev/ttyUSB0", EMFILE, std::nullopt),
            "cannot open /dev/ttyUSB0: Too many open files");
}

// The rule file must name the same device the code looks for, and exist where the
// permission message sends people.
TEST(UdevRule, GrantsAccessToTheDeviceDiscoveryLooksFor) {
  std::ifstream in(std::string(SEQC_SOURCE_DIR) + "/scripts/udev/70-seqc.rules");
  ASSERT_TRUE(in) << "scripts/udev/70-seqc.rules is missing";
  std::stringstream text;
  text << in.rdbuf();
  std::string rule;
  for (std::string line; std::getline(text, line);) {
    if (line.find("hidraw") != std::string::npos && !line.starts_with("#")) rule = line;
  }
  ASSERT_FALSE(rule.empty());
  char ids[96];
  std::snprintf(ids, sizeof ids, "ATTRS{idVendor}==\"%04x\", ATTRS{idProduct}==\"%04x\"",
                kLobotVendorId, kLobotProductId);
  EXPECT_NE(rule.find(ids), std::string::npos) << rule;
  EXPECT_NE(rule.find("ATTRS{product}==\"" + std::string(kLobotProduct) + "\""), std::string::npos)
      << rule;
  EXPECT_NE(rule.find("KERNEL==\"hidraw*\""), std::string::npos) << rule;
  EXPECT_NE(rule.find("TAG+=\"uaccess\""), std::string::npos) << rule;
  EXPECT_NE(
      permission_denied_message("/dev/hidraw0", std::nullopt).find("scripts/udev/70-seqc.rules"),
      std::string::npos);
}

}  // namespace
}  // namespace seqc::transport
