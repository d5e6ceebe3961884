// The xArm emulator behind the same HidBackend interface the hidapi backend implements
// ("emu:xarm-hid"), so `seqc upload --port emu:xarm-hid` runs the whole HID code path --
// discovery by VID/PID and product string, HidTransport, report framing -- down to report bytes.
//
// Reports as the controller's USB HID interface carries them (docs/protocol/servo-controller.md,
// "Framing"): an output report is 65 bytes for hid_write, report id 0 then the serial frame
// zero-padded to 64 bytes; an input report is 64 bytes starting at 55 55, one frame each, zero
// padded. Only the frame reaches the controller's parser, never the padding; a frame whose LEN
// is below 2 still hands it the header and LEN, so the parser abandons it as on the serial line
// instead of waiting inside it for the next report. A write that is not such a report is refused,
// as the kernel would refuse a report of the wrong size. Time: one report per kReportInterval (a
// full-speed interrupt endpoint polled every 1 ms frame); the frame reaches the emulator when its
// report is delivered. Everything in emulated time on the shared ManualClock.
#pragma once

#include <deque>
#include <memory>
#include <string>

#include "protocol/lsc/lsc_stream.hpp"
#include "runtime/emulator/xarm_emulator.hpp"
#include "runtime/io/clock.hpp"
#include "runtime/transport/hid_backend.hpp"

namespace seqc::emu {

inline constexpr const char* kEmulatedHidPath = "emu:xarm-hid";

class EmulatedHidDevice final : public transport::HidDevice {
 public:
  EmulatedHidDevice(XArmEmulator& emulator, io::ManualClock& clock);

  Result<std::size_t> write(ByteView report) override;
  transport::HidRead read(std::span<std::uint8_t> report, int timeout_ms) override;

  // Every output report written, as hid_write received it (tests assert exact bytes).
  const std::vector<Bytes>& reports_written() const { return written_; }
  // Every input report handed to the host.
  const std::vector<Bytes>& reports_read() const { return read_; }

 private:
  void collect();  // emulator output due now -> whole frames -> queued input reports

  XArmEmulator& emu_;
  io::ManualClock& clock_;
  io::TimePoint next_slot_{0};
  lsc::FrameDecoder out_frames_;
  std::deque<Bytes> inbox_;
  std::vector<Bytes> written_;
  std::vector<Bytes> read_;
};

class EmulatedHidBackend final : public transport::HidBackend {
 public:
  EmulatedHidBackend(XArmEmulator& emulator, io::ManualClock& clock)
      : emu_(emulator), clock_(clock) {}

  // One device: 0483:5750 "LOBOT" at kEmulatedHidPath.
  Result<std::vector<transport::HidDeviceInfo>> enumerate(std::uint16_t vendor_id,
                                                          std::uint16_t product_id) override;
  Result<std::unique_ptr<transport::HidDevice>> open(const std::string& path) override;
  // The device the last open() returned (owned by the transport that holds it).
  EmulatedHidDevice* last_opened() const { return last_; }

 private:
  XArmEmulator& emu_;
  io::ManualClock& clock_;
  EmulatedHidDevice* last_ = nullptr;
};

}  // namespace seqc::emu
