// Configuration of the emulated servo controller: timing, servos on the bus, and the faults it
// injects on purpose. Everything here is plain data; the same config and seed always give the
// same behaviour.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "base/result.hpp"
#include "runtime/emulator/group_store.hpp"
#include "runtime/io/clock.hpp"

namespace seqc::emu {

// Faults, all deterministic from `seed`. Rates are per frame, 0..1.
struct XArmFaults {
  std::uint64_t seed = 1;
  double drop = 0;      // an incoming frame is lost (no effect, no reply)
  double corrupt = 0;   // a byte is flipped anywhere in a reply or a request; a request whose
                        // 55 55 LEN is hit is ignored, any other is taken as it arrived
  double late_ack = 0;  // a reply is sent late_by later than normal
  io::Duration late_by = std::chrono::milliseconds(400);
  double duplicate_ack = 0;                 // a reply is sent twice
  std::optional<std::size_t> silent_after;  // stop answering after this many frames received
  std::optional<std::size_t> hangup_at;     // hang up (link closes) when frame N (1-based) arrives
  // After a hang-up the device comes back (the port can be opened again) this much later;
  // unset = it stays away.
  std::optional<io::Duration> back_after;
  // Controller reset (a power dip): the frame that arrives is lost, the controller forgets a
  // download in progress (its group stays empty), stops playing and is deaf for boot_time,
  // then answers as after power-on. Per frame (`reset`), or at frame N (`reset_at`).
  double reset = 0;
  std::optional<std::size_t> reset_at;
  io::Duration boot_time = std::chrono::milliseconds(300);
  // Busy controller: processing a frame takes busy_for longer (its reply comes that much
  // later and frames arriving meanwhile are dropped, as while erasing flash).
  double busy = 0;
  io::Duration busy_for = std::chrono::milliseconds(400);
  // Not the firmware's behaviour (it waits for the rest of a frame however long): the request
  // parser discards a partial frame when the next byte comes more than frame_gap after the one
  // before, so a LEN corrupted upwards cannot swallow the frames that follow. 0 = off.
  io::Duration frame_gap{0};
  // Replies reach the host in two pieces, split at a random point, as a USB-serial adapter
  // flushes part of a reply when its latency timer runs out (the second piece follows once its
  // bytes are due). Per reply.
  double split = 0;
  // The controller's oscillator is this many parts per million fast (slow when negative):
  // stored groups play their action times that much quicker in host time
  // (runtime/emulator/board_clock.hpp). Not a fault of the link, so not one of any().
  std::int32_t clock_ppm = 0;

  bool any() const;
};

// Every key parse_faults takes, with its kind of value and what it does, in the order `seqc
// emulate --help` lists them. parse_faults refuses a key that is not here, and the help is made
// from this table, so neither can name a fault the other does not know.
enum class FaultValue { Rate, Duration, Count, Seed, ClockError };
struct FaultKey {
  std::string_view key;
  FaultValue value;
  std::string_view does;  // "an incoming frame is lost"
};
std::span<const FaultKey> fault_keys();

// Parses "drop=0.01,corrupt=0.01,late=0.01,late-by=400ms,dup=0.01,silent-after=100,
// hangup-at=500,back-after=2s,reset=0.001,reset-at=300,boot-time=300ms,busy=0.01,
// busy-for=400ms,frame-gap=20ms,split=0.1,clock=+0.8%,seed=7" (any subset, any order; "" = no
// faults). Durations take ns, us, ms or s (a bare number is milliseconds); the clock's error a
// percent or ppm (+0.8%, -1%, +120ppm). Unknown keys, rates outside 0..1 and malformed numbers are
// errors naming the offending item.
Result<XArmFaults> parse_faults(std::string_view spec);

// The spec form of `faults` (only non-default items), e.g. "drop=0.05,seed=7"; "none" if none.
std::string describe_faults(const XArmFaults& faults);

// Servo positions at power-on, "1=300,2=650" (ids 1-253, positions 0-1000): the robot as it was
// posed by hand, for `seqc teach` and `seqc servo read` without hardware.
using ServoPositions = std::vector<std::pair<std::uint8_t, std::uint16_t>>;
Result<ServoPositions> parse_positions(std::string_view spec);

struct XArmConfig;
// The options `--port emu:xarm?...` takes: the fault items of parse_faults, servo positions
// (numeric keys: "1=300,drop=0.01"), baud=N (0 = unpaced), and the flash's size: groups=N (group
// numbers 0..N-1, 1-255) and flash=N (actions over every group, 1-260100). Applies them to
// `config`.
Status apply_emulator_options(std::string_view spec, XArmConfig& config);

struct XArmConfig {
  std::uint32_t baud = 0;        // 0 = unpaced; else every byte, either way, takes 10 bits on
                                 // the wire (requests: InputLine in front of the emulator)
  io::Duration command_time{0};  // processing time of an ordinary frame (busy meanwhile)
  io::Duration flash_erase_time = std::chrono::milliseconds(60);  // GroupDownload step 1 and
                                                                  // GroupErase busy time
  io::Duration flash_write_time = std::chrono::milliseconds(2);   // step 4 busy time
  std::uint16_t battery_mv = 7500;
  XArmFaults faults;
  StoreLimits store;  // how many groups and actions the flash holds

  // Bus servos attached: ids 1..servo_count (xArm: 6 bus servos, 0..1000, centre 500).
  std::size_t servo_count = 6;
  std::uint16_t servo_min = 0;
  std::uint16_t servo_max = 1000;
  std::uint16_t servo_home = 500;
  std::uint8_t servo_temperature_c = 32;  // what BusServoInfoRead reports
  ServoPositions initial_positions;       // power-on positions other than home
};

}  // namespace seqc::emu
