#include "runtime/audio/playback_sync.hpp"

#include <cmath>

namespace seqc::audio {

io::TimePoint PlaybackClock::started() const {
  if (sample_rate <= 0) return at;
  // Rounded to the nanosecond: a frame count over a rate is rarely a whole number of them.
  const double ns = static_cast<double>(written) * 1e9 / sample_rate;
  return at - io::Duration{std::llround(ns)};
}

std::int64_t PlaybackClock::heard_frame() const {
  const double behind = std::chrono::duration<double>(latency).count() * sample_rate;
  return written - static_cast<std::int64_t>(std::llround(behind));
}

io::Duration wire_time(std::size_t bytes, double seconds_per_byte) {
  return io::Duration{std::llround(static_cast<double>(bytes) * seconds_per_byte * 1e9)};
}

StartPlan plan_start(const PlaybackClock& clock, const StartTiming& timing) {
  StartPlan p;
  p.audio_started = clock.started();
  p.latency = clock.latency;
  p.downbeat_heard = p.audio_started + p.latency + timing.downbeat + timing.audio_offset;
  p.arrive_at = p.downbeat_heard - timing.board_delay;
  p.write_at = p.arrive_at - timing.wire;
  return p;
}

}  // namespace seqc::audio
