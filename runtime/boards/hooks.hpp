// What a caller may put in place of the system's devices when a port is opened (ports.hpp):
// emulators it prepared itself, so tests can set faults or stored groups first and read what
// the emulator received afterwards, and the device list discovery sees. Every field is
// optional; an empty Hooks means the system's devices and a fresh emulator per emu:NAME port.
#pragma once

namespace seqc::emu {
class XArmEmulator;
class Lsc6Emulator;
}  // namespace seqc::emu

namespace seqc::io {
class ManualClock;
}  // namespace seqc::io

namespace seqc::transport {
class DeviceLister;
}  // namespace seqc::transport

namespace seqc::boards {

struct Hooks {
  emu::XArmEmulator* xarm = nullptr;  // emu:xarm reaches this one (its config holds its faults)
  emu::Lsc6Emulator* lsc6 = nullptr;  // emu:lsc6 reaches this one
  // The time of both; the emulator hooks apply only when this is set.
  io::ManualClock* emulated_clock = nullptr;
  const transport::DeviceLister* lister = nullptr;  // what discovery sees; null: the system's
};

}  // namespace seqc::boards
