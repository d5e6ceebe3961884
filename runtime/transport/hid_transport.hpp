// The xArm controller over USB HID as an io::Transport. The controller speaks the serial frame
// format inside 64-byte reports, so this transport translates at the edges and the uploader
// sees ordinary serial bytes both ways:
//   write(): one whole serial frame -> lsc::encode_hid_report (report id 0, zero padding).
//   read():  one input report -> lsc::decode_hid_report (padding dropped by LEN) ->
//            lsc::encode_serial, handed out in as many reads as the caller's buffer needs.
//
// After an unplug (HangUp), reopen() finds the same controller again, as the serial transport
// does, polling the backend until its deadline on the clock passed in: a controller with a USB
// serial number is known by it (its hidraw node may change when it re-enumerates); one without
// is known by its path. Another controller plugged in meanwhile is never taken for it.
#pragma once

#include <memory>
#include <string>

#include "runtime/io/clock.hpp"
#include "runtime/io/transport.hpp"
#include "protocol/lsc/lsc_frame.hpp"
#include "runtime/transport/hid_backend.hpp"

namespace seqc::transport {

// What reopen() needs: the backend the device was opened with (shared, so it outlives the
// device) and the device as it was found. No backend: reopen() cannot reconnect.
struct HidReconnect {
  std::shared_ptr<HidBackend> backend;
  HidDeviceInfo device;  // path always; serial number and product when enumerated
};

class HidTransport final : public io::Transport {
 public:
  // `description` is what describe() returns, e.g. "hid:/dev/hidraw3 (0483:5750 LOBOT)".
  HidTransport(std::unique_ptr<HidDevice> device, io::Clock& clock, std::string description,
               HidReconnect reconnect = {});

  // Exactly one whole serial frame (55 55 LEN CMD DATA) of at most 64 bytes per call.
  Status write(ByteView bytes) override;
  io::ReadResult read(std::span<std::uint8_t> buffer, io::TimePoint deadline) override;
  // Drops reports queued in the device (read with no wait until none is left) and any part of
  // a report not yet handed out. The uploader calls it before a download.
  void discard_input() override;
  std::string describe() const override { return description_; }
  // One output report per polling interval of the interrupt endpoint: at full speed no shorter
  // than a 1 ms USB frame (the controller's own bInterval may be longer: a reading).
  io::Duration frame_interval() const override { return kReportInterval; }
  // A serial frame travels in one 64-byte report.
  std::size_t max_frame_bytes() const override { return lsc::kHidReportData; }
  static constexpr io::Duration kReportInterval = std::chrono::milliseconds(1);
  // Waits until `deadline` for the same controller to come back, looking every kReopenPoll.
  bool reopen(io::TimePoint deadline) override;
  static constexpr io::Duration kReopenPoll = std::chrono::milliseconds(50);

  // At most this many queued reports are dropped by one discard_input(), so a device that
  // never stops sending cannot hold the caller forever.
  static constexpr int kMaxDrainedReports = 1024;

 private:
  std::size_t hand_out(std::span<std::uint8_t> buffer);
  // One attempt of reopen().
  bool reopen_once();
  bool is_same_device(const HidDeviceInfo& info) const;

  std::unique_ptr<HidDevice> device_;
  io::Clock& clock_;
  std::string description_;
  Bytes pending_;  // serial bytes of the last report not yet read
  std::size_t pending_pos_ = 0;
  HidReconnect reconnect_;
};

}  // namespace seqc::transport
