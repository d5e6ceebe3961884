// When to send a robot its start command so that bar 1 beat 1 of its sequence happens at the
// song's downbeat as heard. Every figure is on the host's monotonic clock:
//
//   downbeat heard = audio start + the API's output latency + downbeat + audio offset
//   arrive         = downbeat heard - the board's start delay
//   write          = arrive - the start command's wire time (bytes x 10 bits / baud)
//
// The audio offset is what no API sees (speakers, a Bluetooth link; negative when the sound is
// heard earlier than the API says). The robot's start is the instant its start command finishes
// arriving at the board, plus the board's own start delay; so the command is written one wire
// time earlier. Pure arithmetic: no clock is read here.
#pragma once

#include <cstddef>

#include "runtime/audio/audio_output.hpp"
#include "runtime/io/clock.hpp"

namespace seqc::audio {

struct StartTiming {
  io::Duration downbeat{0};      // where bar 1 beat 1 falls in the audio
  io::Duration audio_offset{0};  // --audio-offset
  io::Duration wire{0};          // the start command's time on the wire
  io::Duration board_delay{0};   // from its last byte arriving to the motion starting
};

struct StartPlan {
  io::TimePoint audio_started{0};
  io::Duration latency{0};  // the API's output latency
  io::TimePoint downbeat_heard{0};
  io::TimePoint arrive_at{0};  // the start command's last byte at the board
  io::TimePoint write_at{0};   // its first byte written
};

StartPlan plan_start(const PlaybackClock& clock, const StartTiming& timing);

// `bytes` on a link of `seconds_per_byte` (10 bits / baud), to the nanosecond.
io::Duration wire_time(std::size_t bytes, double seconds_per_byte);

}  // namespace seqc::audio
