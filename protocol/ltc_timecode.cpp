#include "protocol/ltc_timecode.hpp"

#include <array>
#include <cstdio>

namespace seqc::ltc {
namespace {

constexpr std::int64_t kDropFramesPerTenMinutes = 17982;  // 10 x 1800 - 9 x 2
constexpr std::int64_t kDropFramesPerMinute = 1798;       // a minute that skips two labels

bool is_digit(char c) { return c >= '0' && c <= '9'; }

}  // namespace

int nominal_fps(FrameRate rate) {
  switch (rate) {
    case FrameRate::Fps24:
      return 24;
    case FrameRate::Fps25:
      return 25;
    case FrameRate::Fps2997Drop:
    case FrameRate::Fps30:
      return 30;
  }
  return 30;
}

double real_fps(FrameRate rate) {
  return rate == FrameRate::Fps2997Drop ? 30000.0 / 1001.0 : nominal_fps(rate);
}

std::string rate_name(FrameRate rate) {
  switch (rate) {
    case FrameRate::Fps24:
      return "24 fps";
    case FrameRate::Fps25:
      return "25 fps";
    case FrameRate::Fps2997Drop:
      return "29.97 fps drop-frame";
    case FrameRate::Fps30:
      return "30 fps";
  }
  return "30 fps";
}

bool exists_at(const Timecode& tc, FrameRate rate) {
  if (tc.hours < 0 || tc.hours > 23 || tc.minutes < 0 || tc.minutes > 59 || tc.seconds < 0 ||
      tc.seconds > 59 || tc.frames < 0 || tc.frames >= nominal_fps(rate)) {
    return false;
  }
  if (rate == FrameRate::Fps2997Drop && tc.seconds == 0 && tc.frames < 2 && tc.minutes % 10 != 0) {
    return false;
  }
  return true;
}

std::int64_t frame_count(const Timecode& tc, FrameRate rate) {
  const std::int64_t minutes = std::int64_t{tc.hours} * 60 + tc.minutes;
  std::int64_t count = (minutes * 60 + tc.seconds) * nominal_fps(rate) + tc.frames;
  if (rate == FrameRate::Fps2997Drop) count -= 2 * (minutes - minutes / 10);
  return count;
}

Timecode to_timecode(std::int64_t count, FrameRate rate) {
  const int fps = nominal_fps(rate);
  const std::int64_t per_day = rate == FrameRate::Fps2997Drop ? 24 * 6 * kDropFramesPerTenMinutes
                                                              : std::int64_t{86400} * fps;
  count %= per_day;
  if (count < 0) count += per_day;
  if (rate == FrameRate::Fps2997Drop) {
    // Put back the labels skipped before `count`: 18 in every whole ten minutes, 2 in every
    // whole minute after the first of the ten.
    const std::int64_t tens = count / kDropFramesPerTenMinutes;
    const std::int64_t rest = count % kDropFramesPerTenMinutes;
    count += 18 * tens;
    if (rest > 1) count += 2 * ((rest - 2) / kDropFramesPerMinute);
  }
  Timecode tc;
  tc.frames = static_cast<int>(count % fps);
  const std::int64_t seconds = count / fps;
  tc.seconds = static_cast<int>(seconds % 60);
  tc.minutes = static_cast<int>(seconds / 60 % 60);
  tc.hours = static_cast<int>(seconds / 3600);
  tc.drop_frame = rate == FrameRate::Fps2997Drop;
  return tc;
}

double frame_start_ms(std::int64_t count, FrameRate rate) {
  return static_cast<double>(count) * 1000.0 / real_fps(rate);
}

std::string to_text(const Timecode& tc) {
  std::array<char, 32> text{};
  std::snprintf(text.data(), text.size(), "%02d:%02d:%02d%c%02d", tc.hours, tc.minutes, tc.seconds,
                tc.drop_frame ? ';' : ':', tc.frames);
  return text.data();
}

Result<Timecode> parse_timecode(std::string_view text) {
  const Error shape =
      make_error("expected a timecode HH:MM:SS:FF (HH:MM:SS;FF for drop-frame), got \"" +
                 std::string(text) + "\"");
  std::array<int, 4> fields{};
  std::array<char, 3> separators{};
  std::size_t at = 0;
  for (std::size_t field = 0; field < fields.size(); ++field) {
    if (field > 0) {
      if (at >= text.size()) return shape;
      const char sep = text[at++];
      if (sep != ':' && sep != ';' && sep != '.') return shape;
      separators[field - 1] = sep;
    }
    const std::size_t from = at;
    int value = 0;
    while (at < text.size() && is_digit(text[at]) && at - from < 2) {
      value = value * 10 + (text[at] - '0');
      ++at;
    }
    if (at == from) return shape;
    fields[field] = value;
  }
  if (at != text.size()) return shape;
  Timecode tc{fields[0], fields[1], fields[2], fields[3], separators[2] != ':'};
  // Drop-frame written with every separator ';' or '.' is also common; a mixed "10;00:00:00"
  // is not a timecode anyone writes.
  if (separators[0] != ':' || separators[1] != ':') {
    if (separators[0] != separators[2] || separators[1] != separators[2]) return shape;
  }
  if (tc.hours > 23)
    return make_error("hours " + std::to_string(tc.hours) + " is past 23 in " + std::string(text));
  if (tc.minutes > 59)
    return make_error("minutes " + std::to_string(tc.minutes) + " is past 59 in " +
                      std::string(text));
  if (tc.seconds > 59)
    return make_error("seconds " + std::to_string(tc.seconds) + " is past 59 in " +
                      std::string(text));
  if (tc.frames > 29)
    return make_error("frame " + std::to_string(tc.frames) + " is past 29 (30 fps) in " +
                      std::string(text));
  if (tc.drop_frame && !exists_at(tc, FrameRate::Fps2997Drop)) {
    return make_error(std::string(text) +
                      " does not exist in drop-frame timecode (frames 0 and 1 are skipped at "
                      "every minute but each tenth)");
  }
  return tc;
}

}  // namespace seqc::ltc
