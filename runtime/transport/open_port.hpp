// Opens the transport a PortSpec names. Emulator specs are built by the caller
// (runtime/emulator's EmulatorTransport); passing one here is an error.
#pragma once

#include <cstdint>
#include <memory>

#include "runtime/io/clock.hpp"
#include "runtime/io/transport.hpp"
#include "runtime/transport/hid_backend.hpp"
#include "runtime/transport/port_spec.hpp"

namespace seqc::transport {

// Serial: spec.baud, else `default_baud`. Hid with an empty path: the one LOBOT device
// (error when there is none or more than one). Errors are ready for "seqc: error: ".
// A HID transport uses `hid` again to reconnect (Transport::reopen): `hid` must outlive it.
Result<std::unique_ptr<io::Transport>> open_port(const PortSpec& spec, io::Clock& clock,
                                                 std::uint32_t default_baud, HidBackend& hid);

// The same with the system's hidapi.
Result<std::unique_ptr<io::Transport>> open_port(const PortSpec& spec, io::Clock& clock,
                                                 std::uint32_t default_baud);

}  // namespace seqc::transport
