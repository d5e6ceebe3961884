// An emulated xArm / LSC-family servo controller, behaving as
// docs/protocol/servo-controller.md describes, including its faults, in EMULATED time: it
// never reads a clock; callers pass the time at which bytes arrive and up to which time runs.
//
// Behaviour (request -> effect; reply, if any):
// Servos are addressed as on the bus (servo_model.hpp): id 254 reaches every servo, and a read
// of 254 is answered by none (docs/protocol/readings.md).
//   MultiServoMove      servos move linearly to their targets over the time; 0xff00 = stay
//   GroupDownload 1-5   the enforced handshake of group_store.hpp; ack 55 55 04 05 <step> 00|01
//   GroupRun            plays a stored group (nothing if the group is empty);
//                       GroupStarted 55 55 05 06 G tLo tHi
//   GroupStop           stops playback (servos finish their current move); GroupStopped
//                       55 55 02 07 (kGroupStoppedHasData: the data-less form)
//   GroupErase          erases one group or all (255), busy for flash_erase_time; 55 55 02 08
//   GroupSpeed          sets a group's (or all groups') speed %, applied at once to a playing
//                       group; volatile (back to 100 at power cycle); 0 is ignored
//   GetBatteryVoltage   55 55 04 0f <battery_mv LE>
//   MultiServoOff       the servos stop where they are and go limp
//   ServoPositionRead   55 55 LEN 15 count {id posLo posHi}, positions at the time the
//                       request is processed (also mid-move); unknown ids are left out
//   ServoOffsetAdjust   volatile offset (-128..127, else ignored), as a short or, in the
//                       one-byte form, an sbyte; ServoOffsetWrite keeps it
//   ServoOffsetRead     55 55 LEN 17 count {id offset}; unknown ids are left out
//   ServoSpeed          stores mode (servo/motor) and milliseconds per servo
//   BusServoInfoWrite   every servo on the bus takes the limits (kept over power cycles);
//                       positions are clamped to them from then on. The id-only form
//                       (55 55 03 1b id): every servo takes the id (0..253, kept; else ignored)
//   BusServoInfoRead    55 55 LEN 1c with the first servo's info (the emulated bus answers
//                       for its first servo), battery millivolts and the configured temperature
// While playing, the controller sends GroupFinished 55 55 05 08 G tLo tHi when a run of
// `times` loops ends (times = 0 loops forever).
//
// Timing: receive() is the moment bytes reach the controller; their wire time from the host
// is modelled in front of it by an InputLine (serial_line.hpp), in ControllerPtyDevice and
// EmulatorTransport alike. A frame is processed when its last byte arrives and keeps the
// controller busy for command_time (flash_erase_time for step 1 and GroupErase,
// flash_write_time for step 4); a frame arriving while busy is dropped silently
// (ReceivedFrame::dropped_busy). The reply is ready when processing ends and then takes
// 10 bits per byte at `baud` (0 = at once).
// Unknown commands and malformed frames are ignored (recorded with frame = nullopt when they
// cannot be framed, or with their frame when they cannot be decoded).
//
// Like the firmware, the request parser has no inter-byte timeout: a frame waits for its last
// byte however long (the frame-gap fault adds one).
// Faults (XArmFaults): drawn once per framed request and once per outgoing frame, so the same
// seed and the same input give the same received() and the same output, byte for byte.
// Silence (silent_after) stops all further output and processing; a hang-up closes the link:
// nothing is received or sent after it, until reconnect() when the faults let the device come
// back (back_after; the controller kept its power and its state, bytes in flight are lost).
// A reset (power dip) is power_cycle() as the frame arrives, then boot_time of deafness.
// A busy fault lengthens one frame's processing by busy_for.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "base/bytes.hpp"
#include "protocol/lsc/group_download.hpp"
#include "protocol/lsc/lsc_frame.hpp"
#include "protocol/lsc/lsc_messages.hpp"
#include "runtime/emulator/controller_device.hpp"
#include "runtime/emulator/fault_injector.hpp"
#include "runtime/emulator/group_player.hpp"
#include "runtime/emulator/group_store.hpp"
#include "runtime/emulator/serial_line.hpp"
#include "runtime/emulator/servo_model.hpp"
#include "runtime/emulator/xarm_config.hpp"
#include "runtime/io/clock.hpp"

namespace seqc::emu {

// Modelling choice: GroupStop is answered with the data-less CMD 7 frame (55 55 02 07) that
// docs/protocol/servo-controller.md reports for some boards; the host must accept both forms
// anyway.
inline constexpr bool kGroupStoppedHasData = false;

struct ReceivedFrame {
  io::TimePoint at{0};
  Bytes raw;                              // as the controller saw it (after injected corruption)
  std::optional<lsc::Frame> frame;        // nullopt: could not be framed (garbage, bad LEN, cut)
  bool dropped_busy = false;              // arrived while the controller was busy
  bool dropped_fault = false;             // lost, corrupted, unanswered or hung up by a fault
  DropReason dropped = DropReason::None;  // which of those, and which fault
  // The byte a `corrupt` fault flipped, when it was past 55 55 LEN: the controller took the
  // frame as it arrived (raw and frame hold the flipped byte).
  std::optional<std::size_t> flipped_at;
};

class XArmEmulator final : public ControllerDevice {
 public:
  explicit XArmEmulator(XArmConfig config = {});

  // Bytes arrive, all at `at` (a time before the emulator's present counts as the present).
  // Ignored once hung up.
  void receive(ByteView bytes, io::TimePoint at) override;
  // Runs emulated time up to `t`: motion, playback, notifications.
  void advance_to(io::TimePoint t) override;
  // When the next output byte is due (a lower bound while a group notification is pending:
  // the caller advances to it and asks again). nullopt when nothing will come.
  std::optional<io::TimePoint> next_output_at() const override;
  // When the last byte of the next message out is due (for a caller that hands output over
  // in whole messages); the same lower bound as next_output_at() for a pending notification.
  std::optional<io::TimePoint> next_message_end_at() const override;
  // Advances to `upto` and returns the output bytes due at or before it.
  Bytes take_output(io::TimePoint upto) override;

  bool hung_up() const override { return hung_up_; }
  // When the device can be reached again after a hang-up; nullopt if it stays away.
  std::optional<io::TimePoint> back_at() const override;
  // The host opens the port again at `at`: true (and the link works again) if the device is
  // back by then.
  bool reconnect(io::TimePoint at) override;
  std::uint32_t baud() const override { return config_.baud; }
  io::Duration frame_gap() const override { return config_.faults.frame_gap; }
  std::string port_name() const override { return "emu:xarm"; }
  // Resets (power dips) injected so far.
  std::size_t resets() const { return resets_; }
  // Every piece received, in order: frames, unframeable bytes, dropped frames.
  const std::vector<ReceivedFrame>& received() const { return received_; }
  // All bytes ever passed to receive(), concatenated, as the host wrote them.
  Bytes received_bytes() const { return received_bytes_; }
  // nullopt = empty.
  std::optional<std::vector<lsc::GroupAction>> stored_group(std::uint8_t group) const;
  // Position on the trajectory known now (call advance_to first for playback beyond now()).
  std::uint16_t servo_position(std::uint8_t id, io::TimePoint at) const;

  // Power cycle at `at`: flash (groups, written offsets, servo limits) survives; volatile
  // state (adjusted offsets, group speeds, servo modes, playback, a download in progress,
  // pending output, a busy period) is lost. A download in progress leaves its group empty.
  void power_cycle(io::TimePoint at);
  // Moves a limp servo (after MultiServoOff) by hand, as during teach-in; false if it is
  // powered (it holds) or not on the bus.
  bool pose_by_hand(std::uint8_t id, std::uint16_t position, io::TimePoint at);

  io::TimePoint now() const { return now_; }
  const XArmConfig& config() const { return config_; }
  std::optional<std::uint8_t> downloading_group() const { return downloader_.active_group(); }
  std::optional<std::uint8_t> playing_group() const { return player_.group(); }
  std::uint16_t group_speed(std::uint8_t group) const { return speeds_[group]; }
  const ServoBank& servos() const { return servos_; }
  // Framed requests received so far (the count faults are numbered by).
  std::size_t frames_received() const { return faults_.frames_seen(); }
  // Frames sent so far (replies and notifications; the count reply faults are drawn for).
  std::size_t frames_sent() const { return faults_.replies_seen(); }

 private:
  struct Processed {
    io::Duration busy{0};
    std::vector<lsc::Frame> replies;
  };
  void handle_piece(RequestFramer::Piece piece, io::TimePoint at);
  Processed process(const lsc::Frame& frame, io::TimePoint at);
  void emit(const lsc::Frame& frame, io::TimePoint ready);

  XArmConfig config_;
  FaultInjector faults_;
  RequestFramer framer_;
  OutputLine line_;
  ServoBank servos_;
  GroupStore store_;
  GroupDownloader downloader_;
  GroupPlayer player_;
  std::vector<std::uint16_t> speeds_;
  io::TimePoint now_{0};
  io::TimePoint busy_until_{0};
  bool hung_up_ = false;
  io::TimePoint hung_up_at_{0};
  std::size_t resets_ = 0;
  std::vector<ReceivedFrame> received_;
  Bytes received_bytes_;
};

}  // namespace seqc::emu
