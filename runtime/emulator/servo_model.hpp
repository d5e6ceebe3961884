// The bus servos attached to the emulated controller: linear motion over the commanded time,
// offsets (volatile "adjust" vs kept "write"), motor/servo mode and the limits written by
// BusServoInfoWrite. Positions are computed from the trajectory at the time asked, so they
// can be read while a servo is moving.
//
// Addressing, as on the bus (docs/protocol/readings.md): every servo hears every command; the
// ones whose id matches obey, and id 254 (kBroadcastId) reaches them all. Servos start with ids
// 1..count; BusServoInfoWrite's id-only form gives every servo one new id (kept over power
// cycles). Commands that change a servo act on every servo with that id; a read names one, the
// first on the bus with that id (several would answer at once on a real bus). Nothing answers a
// read of 254: a bus servo does not reply to the broadcast id.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "protocol/lsc/lsc_messages.hpp"
#include "runtime/io/clock.hpp"

namespace seqc::emu {

inline constexpr std::uint8_t kBroadcastId = 254;
inline constexpr std::uint8_t kMaxServoId = 253;

struct ServoModelConfig {
  std::size_t count = 6;  // ids 1..count
  std::uint16_t min = 0;
  std::uint16_t max = 1000;
  std::uint16_t home = 500;
  // Where servos stand at power-on instead of home (as if posed by hand): id, position.
  std::vector<std::pair<std::uint8_t, std::uint16_t>> initial;
};

class ServoBank {
 public:
  explicit ServoBank(const ServoModelConfig& config);

  bool has(std::uint8_t id) const;
  // Each servo's id, in bus order (the same id more than once after an id-only write).
  std::vector<std::uint8_t> ids() const;

  // Moves linearly from wherever the servo is at `start` to `target` (clamped to the servo's
  // position limits), arriving at start + duration. Powers the servo on.
  void move(std::uint8_t id, std::uint16_t target, io::Duration duration, io::TimePoint start);
  // Unpowers the servo: it stops where it is at `at`.
  void power_off(std::uint8_t id, io::TimePoint at);
  // A person moving a limp servo by hand; a powered servo holds against the hand (false).
  bool pose_by_hand(std::uint8_t id, std::uint16_t position, io::TimePoint at);
  bool powered(std::uint8_t id) const;
  std::uint16_t position(std::uint8_t id, io::TimePoint at) const;

  void adjust_offset(std::uint8_t id, std::int8_t offset);  // volatile
  void write_offset(std::uint8_t id);                       // keeps the current offset
  std::int8_t offset(std::uint8_t id) const;
  std::int8_t stored_offset(std::uint8_t id) const;

  void set_mode(std::uint8_t id, lsc::ServoMode mode, std::uint16_t milliseconds);
  lsc::ServoMode mode(std::uint8_t id) const;
  std::uint16_t mode_milliseconds(std::uint8_t id) const;

  // BusServoInfoWrite reaches every servo on the bus: all take the limits (kept over power-off).
  void write_limits(const lsc::BusServoLimits& limits);
  // ... and its id-only form gives them all the id `id` (0..253; anything else is ignored).
  void write_id(std::uint8_t id);
  lsc::BusServoLimits limits(std::uint8_t id) const;

  // Power cycle at `at`: servos hold where they are, volatile offsets revert to the written
  // ones, mode returns to servo mode.
  void power_cycle(io::TimePoint at);

 private:
  struct Servo {
    std::uint8_t id = 0;
    std::uint16_t from = 0;
    std::uint16_t to = 0;
    io::TimePoint t0{0};
    io::TimePoint t1{0};
    bool powered = true;
    std::int8_t offset = 0;
    std::int8_t stored_offset = 0;
    lsc::ServoMode mode = lsc::ServoMode::Servo;
    std::uint16_t mode_ms = 0;
    lsc::BusServoLimits limits;
  };
  const Servo* find(std::uint8_t id) const;  // the first servo with this id
  Servo* find(std::uint8_t id);
  // Calls `f` for every servo that obeys a command addressed to `id`.
  template <class F>
  void for_each(std::uint8_t id, F f) {
    for (Servo& s : servos_) {
      if (s.id == id || id == kBroadcastId) f(s);
    }
  }
  static std::uint16_t at_time(const Servo& s, io::TimePoint at);

  std::vector<Servo> servos_;  // in bus order
};

}  // namespace seqc::emu
