// An emulated LSC-6 / LeArm controller running the family's six-channel firmware
// (docs/protocol/lsc-6.md), in EMULATED time: callers pass the time bytes reach it.
//
// Receiver (byte by byte, as the firmware's interrupt routine): 55 55 starts a frame; a LEN
// below 2 abandons it; the frame is complete after LEN + 2 bytes counted in a byte-wide counter,
// so a LEN of 254 or 255 never completes: the receiver swallows what follows until its counter
// wraps and it takes the byte then at position 2 as a new LEN (253 bytes later). There is no
// inter-byte timeout: a frame waits for its last byte however long.
// A completed frame is copied into the one command buffer if that is free (the main loop takes
// it as soon as it is idle); a frame completing while the buffer still holds one is dropped
// without a word.
//
// Main loop (one command at a time; busy meanwhile):
//   Move (3)            servos 0..7 at 500..2500 us move (others ignored), time clamped to
//                       20..30,000 ms; no answer
//   Run (6)             answers 55 55 02 06 first (unless run_reply is off), then starts the
//                       group if it holds actions; a run of another group (not 0) while one
//                       plays is ignored; group 0 pre-empts
//   Stop (7)            stops playback; no answer
//   EraseAll (8)        sets every group's action count to 0 (one sector erase and a table
//                       write); answers 55 55 02 08
//   DownloadAction (25) index 0 erases the group's 16 KiB (four sector erases); the 64 bytes
//                       from the frame's N onwards go to the action's flash slot (bits can
//                       only be cleared, as on NOR flash); the last index (IDX + 1 = TOTAL)
//                       writes the group's count; answers 55 55 02 19 after the write
//   anything else       ignored, no answer
// Each answer keeps the main loop busy for its own wire time (the firmware sends blocking).
// Playback runs the group's actions one after another, each for its stored time; an action
// with more than 8 servos (erased flash reads 0xff) stops it. A counted run that ends sends
// 55 55 02 07 (unless finish_notice is off).
//
// Faults: drop (a fraction of completed frames lost, as on a noisy line), from a seed; clock (the
// board's oscillator fast or slow: every time it counts, a stored action's or a Move's, lasts
// that much less or more host time; board_clock.hpp).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "base/result.hpp"
#include "protocol/lsc6/lsc6_messages.hpp"
#include "runtime/emulator/controller_device.hpp"
#include "runtime/emulator/fault_injector.hpp"
#include "runtime/emulator/serial_line.hpp"

namespace seqc::emu {

struct Lsc6Config {
  std::uint32_t baud = 9600;
  bool run_reply = true;      // copies differ: some never answer Run
  bool finish_notice = true;  // copies differ: some never announce the end of a run
  // SPI NOR flash timings (typical datasheet figures of the 4 KiB-sector parts such boards use).
  io::Duration sector_erase = std::chrono::milliseconds(45);
  io::Duration slot_write = std::chrono::microseconds(700);
  io::Duration table_write = std::chrono::microseconds(1400);  // 256 bytes: one page program
  double drop = 0.0;                                           // fraction of completed frames lost
  std::uint64_t seed = 1;
  std::int32_t clock_ppm = 0;  // the board's clock this many ppm fast (slow when negative)
};

// Every item apply_lsc6_options takes, in the order `seqc emulate --help` lists them: it refuses
// an item not here, and the help is made from this table, so the two cannot drift. `fault`:
// a fault (`seqc emulate lsc6 --faults`), not the line's rate (`--baud`).
struct Lsc6OptionKey {
  std::string_view key;
  std::string_view value;  // "P" (a fraction 0..1), "N" (a whole number), "" (a flag)
  std::string_view does;
  bool fault = true;
};
std::span<const Lsc6OptionKey> lsc6_option_keys();

// "drop=0.05,seed=7,clock=+0.8%,no-run-reply,no-finish" (any subset; "" = defaults). Error names
// the item.
Status apply_lsc6_options(std::string_view spec, Lsc6Config& config);

struct Lsc6Received {
  io::TimePoint at{0};
  Bytes raw;                  // the frame as completed by the receiver
  bool dropped_busy = false;  // the command buffer was still full
  bool dropped_fault = false;
  DropReason dropped = DropReason::None;  // Busy or FaultDrop when one of those is set
};

class Lsc6Emulator final : public ControllerDevice {
 public:
  explicit Lsc6Emulator(Lsc6Config config = {});

  void receive(ByteView bytes, io::TimePoint at) override;
  void advance_to(io::TimePoint t) override;
  std::optional<io::TimePoint> next_output_at() const override;
  std::optional<io::TimePoint> next_message_end_at() const override;
  Bytes take_output(io::TimePoint upto) override;
  bool hung_up() const override { return false; }
  std::optional<io::TimePoint> back_at() const override { return std::nullopt; }
  bool reconnect(io::TimePoint) override { return true; }
  std::uint32_t baud() const override { return config_.baud; }
  io::Duration frame_gap() const override { return io::Duration{0}; }
  std::string port_name() const override { return "emu:lsc6"; }

  // The group's actions as the player would read them (count from the table, each slot
  // decoded); nullopt when the count is 0.
  std::optional<std::vector<lsc6::PlannedAction>> stored_group(std::uint8_t group) const;
  std::uint8_t stored_count(std::uint8_t group) const { return counts_[group]; }
  std::optional<std::uint8_t> playing_group() const;
  // The pulse a channel (0..7) is at, on its current move.
  std::uint16_t pulse(std::uint8_t channel, io::TimePoint at) const;
  // True while the receiver is inside a frame that cannot complete (LEN 254/255).
  bool receiver_wedged() const;
  const std::vector<Lsc6Received>& received() const { return received_; }
  Bytes received_bytes() const { return received_bytes_; }
  io::TimePoint now() const { return now_; }
  // Power cycle: flash survives, everything else starts afresh.
  void power_cycle(io::TimePoint at);

 private:
  struct Channel {
    std::uint16_t from = 1500, to = 1500;
    io::TimePoint start{0};
    io::Duration duration{0};
  };
  struct Playback {
    std::uint8_t group = 0;
    std::uint32_t times = 1;
    std::uint32_t loops = 0;
    std::uint8_t count = 0;  // the firmware's FrameIndexSum (a later Run may change it)
    std::uint8_t index = 0;
    io::TimePoint action_end{0};
  };

  void feed_byte(std::uint8_t b, io::TimePoint at);
  void complete_frame(io::TimePoint at);
  io::Duration process(io::TimePoint at);
  void answer(lsc6::Command cmd, io::TimePoint ready);
  // The host time `ms` of the board's own clock lasts.
  io::Duration board_ms(unsigned ms) const;
  void set_servo(std::uint8_t channel, std::uint16_t pulse, std::uint16_t time_ms,
                 io::TimePoint at);
  void full_act_run(std::uint8_t group, std::uint16_t times, io::TimePoint at);
  void play_until(io::TimePoint upto);
  io::Duration play_action(io::TimePoint at);
  std::optional<io::TimePoint> next_playback_event() const;
  std::optional<io::TimePoint> earliest_with_pending(std::optional<io::TimePoint> line_time) const;

  Lsc6Config config_;
  SplitMix64 rng_;
  OutputLine line_;
  io::TimePoint now_{0};
  io::TimePoint busy_until_{0};
  // Receiver state, as the interrupt routine keeps it.
  bool frame_start_ = false;
  std::uint8_t start_count_ = 0;
  std::uint8_t msg_len_ = 0;
  unsigned expected_ = 2;
  std::array<std::uint8_t, 260> rx_{};
  // The command buffer (stale bytes beyond the last frame stay, as in the firmware).
  std::array<std::uint8_t, 260> cmd_{};
  std::optional<io::TimePoint> held_since_;
  // Flash: per group, 256 slots of 64 bytes (none allocated = all erased), and the count table.
  using Slot = std::array<std::uint8_t, lsc6::kSlotBytes>;
  std::vector<std::vector<Slot>> slots_;
  std::array<std::uint8_t, 256> counts_{};
  std::array<Channel, 8> channels_{};
  std::optional<Playback> playing_;
  std::uint8_t last_group_ = 0;  // the firmware's ActFullNum
  std::vector<Lsc6Received> received_;
  Bytes received_bytes_;
};

}  // namespace seqc::emu
