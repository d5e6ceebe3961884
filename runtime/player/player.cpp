#include "runtime/player/player.hpp"

#include <algorithm>
#include <cmath>

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

void send_safe_stop(io::Transport& transport, const PlayOptions& options, PlayReport& report) {
  if (!options.safe_stop) return;
  if (auto ok = transport.write(*options.safe_stop); ok) {
    report.stop_sent = true;
  } else {
    report.stop_error = ok.error().message;
  }
}

// Byte times are whole nanoseconds on some links and exact on others: differences this small
// are rounding, not lateness.
constexpr io::Duration kRounding = std::chrono::microseconds(1);

io::Duration wire_time(const ScheduledFrame& f, double seconds_per_byte) {
  return std::chrono::duration_cast<io::Duration>(
      std::chrono::duration<double>(static_cast<double>(f.bytes.size()) * seconds_per_byte));
}

}  // namespace

ScheduleCheck check_schedule(const std::vector<ScheduledFrame>& frames, double seconds_per_byte,
                             io::Duration frame_interval) {
  ScheduleCheck c;
  io::Duration line_free{0};
  io::Duration previous{0};
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const io::Duration start = std::max(frames[i].at, line_free);
    if (start > frames[i].at) {
      ++c.late_frames;
      c.worst = std::max(c.worst, start - frames[i].at);
      if (!c.first_late) {
        c.first_late = i;
        c.late_by = start - frames[i].at;
        c.wire_time = previous;
      }
    }
    previous = std::max(wire_time(frames[i], seconds_per_byte), frame_interval);
    line_free = start + previous;
  }
  return c;
}

PlayReport play(const std::vector<ScheduledFrame>& frames, io::Transport& transport,
                io::Clock& clock, const PlayOptions& options) {
  PlayReport report;
  report.started = clock.now();
  report.lateness.reserve(frames.size());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const io::TimePoint deadline = report.started + frames[i].at;
    if (!wait_until(clock, deadline, options)) {
      report.end = PlayEnd::Interrupted;
      send_safe_stop(transport, options, report);
      return report;
    }
    const io::TimePoint begin = clock.now();
    auto written = transport.write(frames[i].bytes);
    const io::TimePoint end = clock.now();
    if (!written) {
      report.end = PlayEnd::WriteFailed;
      report.error = written.error().message;
      send_safe_stop(transport, options, report);
      return report;
    }
    FrameTiming timing{deadline, begin - deadline, end - begin, io::Duration{0}};
    if (options.drain) {
      if (auto drained = transport.drain(); !drained) {
        report.end = PlayEnd::WriteFailed;
        report.error = drained.error().message;
        send_safe_stop(transport, options, report);
        return report;
      }
      // Computed wire times are rounded; a frame cannot leave before its bytes could.
      const io::Duration late =
          clock.now() - (deadline + wire_time(frames[i], options.seconds_per_byte));
      timing.left_lateness = late < kRounding ? io::Duration{0} : late;
      report.left_lateness.push_back(timing.left_lateness);
    }
    ++report.sent;
    report.lateness.push_back(begin - deadline);
    if (options.on_sent) options.on_sent(i, timing);
  }
  return report;
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
