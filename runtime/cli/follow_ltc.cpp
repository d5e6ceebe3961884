#include "runtime/cli/follow_ltc.hpp"

#include <filesystem>
#include <system_error>

#include "runtime/audio/pulse_input.hpp"
#include "runtime/audio/wav_input.hpp"
#include "runtime/follow/ltc_clock.hpp"

namespace seqc::cli {
namespace {

constexpr double kRecordRate = 48000;

bool names_wav(const std::string& source) {
  const std::string ext = std::filesystem::path(source).extension().string();
  return ext == ".wav" || ext == ".WAV" || ext == ".Wav";
}

}  // namespace

Result<ltc::Timecode> parse_ltc_start(const std::string& text) {
  auto start = ltc::parse_timecode(text);
  if (!start) return make_error("--start: " + start.error().message);
  return start;
}

Result<std::unique_ptr<follow::ShowClock>> open_ltc_clock(const std::string& source,
                                                          const ltc::Timecode& start,
                                                          Context& ctx) {
  std::error_code ec;
  const bool is_file = std::filesystem::is_regular_file(source, ec);
  Result<std::unique_ptr<audio::AudioInput>> input = make_error("");
  if (is_file) {
    input = audio::open_wav_input(source, ctx.clock, audio::WavPace::RealTime);
  } else if (names_wav(source)) {
    return make_error("--ltc: " + source + ": no such file");
  } else {
    input = audio::open_pulse_input(ctx.clock, source, kRecordRate, "seqc");
  }
  if (!input) return make_error("--ltc: " + input.error().message);
  follow::LtcClockOptions options;
  options.start = start;
  auto clock = follow::LtcClock::create(std::move(*input), ctx.clock, options);
  if (!clock) return make_error("--ltc: " + clock.error().message);
  return std::unique_ptr<follow::ShowClock>(std::move(*clock));
}

}  // namespace seqc::cli
