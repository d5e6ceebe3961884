#include "runtime/player/player.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace seqc::player {
namespace {

bool is_set(const std::atomic<bool>* flag) { return flag != nullptr && flag->load(); }

// Waits until `deadline` in slices no longer than the poll interval; false if interrupted.
bool wait_until(io::Clock& clock, io::TimePoint deadline, const PlayOptions& options) {
  for (;;) {
    if (is_set(options.interrupted)) return false;
    const io::TimePoint now = clock.now();
    if (now >= deadline) return true;
    clock.sleep_until(std::min(deadline, now + options.poll_interval));
  }
}

// Writes every track's safe stop, in track order; the report's own stop fields are those of
// the first track that has one.
void send_safe_stops(const std::vector<Track>& tracks, PlayReport& report) {
  bool first = true;
  for (std::size_t t = 0; t < tracks.size(); ++t) {
    if (!tracks[t].safe_stop || tracks[t].transport == nullptr) continue;
    TrackReport& r = report.tracks[t];
    if (auto ok = tracks[t].transport->write(*tracks[t].safe_stop); ok) {
      r.stop_sent = true;
    } else {
      r.stop_error = ok.error().message;
    }
    if (first) {
      report.stop_sent = r.stop_sent;
      report.stop_error = r.stop_error;
      first = false;
    }
  }
}

// Byte times are whole nanoseconds on some links and exact on others: differences this small
// are rounding, not lateness.
constexpr io::Duration kRounding = std::chrono::microseconds(1);

// To the nearest nanosecond, as a song's start works it out (audio::wire_time), so a first frame
// timed to a song and the same frame in a schedule are written at the same instant.
io::Duration wire_time(const ScheduledFrame& f, double seconds_per_byte) {
  return io::Duration{std::llround(static_cast<double>(f.bytes.size()) * seconds_per_byte * 1e9)};
}

}  // namespace

ScheduleCheck check_schedule(const std::vector<ScheduledFrame>& frames, double seconds_per_byte,
                             io::Duration frame_interval) {
  ScheduleCheck c;
  io::Duration line_free{0};
  io::Duration previous{0};
  for (std::size_t i = 0; i < frames.size(); ++i) {
    // Written its own wire time early, so it finishes arriving at its time.
    const io::Duration own = wire_time(frames[i], seconds_per_byte);
    const io::Duration due = frames[i].at - own;
    const io::Duration start = i == 0 ? due : std::max(due, line_free);
    if (start > due) {
      ++c.late_frames;
      c.worst = std::max(c.worst, start - due);
      if (!c.first_late) {
        c.first_late = i;
        c.late_by = start - due;
        c.wire_time = previous;
      }
    }
    previous = std::max(own, frame_interval);
    line_free = start + previous;
  }
  return c;
}

PlayReport play(const std::vector<Track>& tracks, io::Clock& clock, const PlayOptions& options) {
  PlayReport report;
  // Without a given start, time enough for the frame due furthest ahead of its `at`.
  io::Duration ahead{0};
  for (const Track& t : tracks) {
    for (const ScheduledFrame& f : t.frames) {
      ahead = std::max(ahead, t.early + wire_time(f, t.seconds_per_byte) - f.at);
    }
  }
  report.started = options.start_at ? *options.start_at : clock.now() + options.lead + ahead;
  report.tracks.resize(tracks.size());
  std::size_t total = 0;
  for (const Track& t : tracks) total += t.frames.size();
  report.lateness.reserve(total);
  std::vector<std::size_t> next(tracks.size(), 0);
  for (;;) {
    // The earliest frame due; ties go to the lower track.
    std::optional<std::size_t> pick;
    auto due = [&](std::size_t t) {
      const ScheduledFrame& f = tracks[t].frames[next[t]];
      return f.at - tracks[t].early - wire_time(f, tracks[t].seconds_per_byte);
    };
    for (std::size_t t = 0; t < tracks.size(); ++t) {
      if (next[t] >= tracks[t].frames.size()) continue;
      if (!pick || due(t) < due(*pick)) pick = t;
    }
    if (!pick) break;
    const std::size_t t = *pick;
    const io::TimePoint deadline = report.started + due(t);
    const std::size_t i = next[t]++;
    const Track& track = tracks[t];
    TrackReport& mine = report.tracks[t];
    const ScheduledFrame& frame = track.frames[i];
    if (!wait_until(clock, deadline, options)) {
      report.end = PlayEnd::Interrupted;
      send_safe_stops(tracks, report);
      return report;
    }
    const io::TimePoint begin = clock.now();
    auto written = track.transport->write(frame.bytes);
    if (!written) {
      report.end = PlayEnd::WriteFailed;
      report.error = written.error().message;
      report.failed_track = t;
      send_safe_stops(tracks, report);
      return report;
    }
    if (!mine.first) mine.first = begin - report.started;
    FrameTiming timing{deadline, begin - deadline, io::Duration{0}, t};
    if (track.drain) {
      if (auto drained = track.transport->drain(); !drained) {
        report.end = PlayEnd::WriteFailed;
        report.error = drained.error().message;
        report.failed_track = t;
        send_safe_stops(tracks, report);
        return report;
      }
      // Computed wire times are rounded; a frame cannot leave before its bytes could.
      const io::Duration late = clock.now() - (deadline + wire_time(frame, track.seconds_per_byte));
      timing.left_lateness = late < kRounding ? io::Duration{0} : late;
      mine.left_lateness.push_back(timing.left_lateness);
      report.left_lateness.push_back(timing.left_lateness);
    }
    ++mine.sent;
    ++report.sent;
    mine.lateness.push_back(begin - deadline);
    report.lateness.push_back(begin - deadline);
    if (options.on_sent) options.on_sent(i, timing);
  }
  return report;
}

PlayReport play(const std::vector<ScheduledFrame>& frames, io::Transport& transport,
                io::Clock& clock, const PlayOptions& options) {
  std::vector<Track> tracks(1);
  tracks[0].transport = &transport;
  tracks[0].frames = frames;
  tracks[0].safe_stop = options.safe_stop;
  tracks[0].drain = options.drain;
  tracks[0].seconds_per_byte = options.seconds_per_byte;
  tracks[0].early = options.early;
  return play(tracks, clock, options);
}

LatenessSummary summarize(std::vector<io::Duration> lateness) {
  LatenessSummary s;
  if (lateness.empty()) return s;
  std::sort(lateness.begin(), lateness.end());
  auto rank = [&](double p) {
    const auto n = static_cast<double>(lateness.size());
    const auto k = static_cast<std::size_t>(std::ceil(p * n));
    return lateness[std::clamp<std::size_t>(k, 1, lateness.size()) - 1];
  };
  s.p50 = rank(0.50);
  s.p99 = rank(0.99);
  s.max = lateness.back();
  return s;
}

}  // namespace seqc::player
