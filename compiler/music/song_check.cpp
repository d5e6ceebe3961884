// check_song() (song_check.hpp).
#include "compiler/music/song_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "compiler/music/beat_analysis.hpp"

namespace seqc::compiler {
namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

std::string seconds(double ms) { return fmt::format("{:.3f} s", ms / 1000); }

// One detected beat against the file's: its beat (counted from 0) and bar (from 1) on the
// file's map, and how much later than the file's beat it falls (ms).
struct BeatOffset {
  long long beat = 0;
  long long bar = 0;
  double ms = 0;
};

// Every detected beat of `beats_s` (audio time, with bar 1 beat 1 at `downbeat_ms`) against the
// nearest beat of `map`, in time order.
std::vector<BeatOffset> beat_offsets(const TempoMap& map, const std::vector<double>& beats_s,
                                     double downbeat_ms) {
  std::vector<BeatOffset> out;
  for (double b : beats_s) {
    const double t = b * 1000 - downbeat_ms;
    if (t < 0) continue;  // a pickup before bar 1: the file has no beats there
    const double beat = map.beat_at(ExactMs::from_double(t)).value();
    const auto k = static_cast<std::int64_t>(std::llround(beat));
    const std::optional<ExactMs> planned = map.time_of_beat(ExactMs(k));
    if (!planned) continue;
    const auto bar = static_cast<long long>(std::floor(map.bar_of_beat(ExactMs(k)).value())) + 1;
    out.push_back({k, bar, t - planned->value()});
  }
  return out;
}

// offset = intercept + slope * beat, by least squares, and the residuals' RMS beside the RMS
// about the mean (what a constant offset leaves).
struct LineFit {
  double intercept = 0;
  double slope = 0;
  double rms_line = 0;
  double rms_flat = 0;
};

LineFit fit_line(const std::vector<BeatOffset>& points) {
  const double n = static_cast<double>(points.size());
  double mk = 0, mo = 0;
  for (const BeatOffset& p : points) {
    mk += static_cast<double>(p.beat) / n;
    mo += p.ms / n;
  }
  double skk = 0, sko = 0;
  for (const BeatOffset& p : points) {
    skk += (static_cast<double>(p.beat) - mk) * (static_cast<double>(p.beat) - mk);
    sko += (static_cast<double>(p.beat) - mk) * (p.ms - mo);
  }
  LineFit f;
  f.slope = skk > 0 ? sko / skk : 0;
  f.intercept = mo - f.slope * mk;
  double line = 0, flat = 0;
  for (const BeatOffset& p : points) {
    const double r = p.ms - (f.intercept + f.slope * static_cast<double>(p.beat));
    line += r * r;
    flat += (p.ms - mo) * (p.ms - mo);
  }
  f.rms_line = std::sqrt(line / n);
  f.rms_flat = std::sqrt(flat / n);
  return f;
}

// The song's tempo as the line to paste gives it: to the tenth a few dozen beats support,
// without trailing zeros ("96", "96.5").
std::string tempo_text(double bpm) {
  std::string t = fmt::format("{:.1f}", bpm);
  while (t.back() == '0') t.pop_back();
  if (t.back() == '.') t.pop_back();
  return t;
}

// The song's samples, or nullopt after an error at the `file:` value.
std::optional<SongSamples> read_song(const SongFile& file, SongReader& reader, Reporter& reporter) {
  Result<SongSamples> audio = reader.read(file.path);
  if (!audio) {
    reporter.error(file.at, "cannot use the song: " + audio.error().message);
    return std::nullopt;
  }
  if (audio->sample_rate <= 0 || audio->samples.empty()) {
    reporter.error(file.at, "cannot use the song: '" + file.path + "' holds no audio");
    return std::nullopt;
  }
  return std::move(*audio);
}

}  // namespace

void check_song_readable(const SongFile& file, SongReader& reader, Reporter& reporter) {
  (void)read_song(file, reader, reporter);
}

void check_song(const Song& song, const TempoMap& map, ExactMs end, SongReader& reader,
                Reporter& reporter) {
  const std::optional<SongSamples> audio =
      read_song(SongFile{song.file, song.file_at}, reader, reporter);
  if (!audio) return;
  const double length_ms = static_cast<double>(audio->samples.size()) / audio->sample_rate * 1000;
  const double downbeat_ms = song.downbeat.value();
  const double dance_end_ms = downbeat_ms + end.value();
  if (dance_end_ms > length_ms + 0.5) {
    reporter.warning(song.at, "the dance runs " + seconds(dance_end_ms - length_ms) +
                                  " past the end of the song (it ends " + seconds(dance_end_ms) +
                                  " into the audio, which lasts " + seconds(length_ms) + ")");
  }

  music::BeatOptions options;
  options.meter = music::Meter{song.meter.beats_per_bar, song.meter.beat_unit};
  options.tempo_hint = song.bpm();
  const Result<music::BeatAnalysis> analysis =
      music::analyze_beats(std::span<const float>(audio->samples), audio->sample_rate, options);
  if (!analysis) {
    reporter.warning(song.file_at,
                     "cannot check the tempo map against the song: " + analysis.error().message);
    return;
  }
  // A bar disagrees when the median of its beats' offsets does (one stray beat does not make
  // it); a disagreement is reported once, from its first bar, and only when it lasts two bars or
  // more (a lone bar is the tracker's doubt, not the map's). An offset that grows steadily with
  // the beat (a line through the offsets explains them) is the wrong tempo, said with the tempo
  // the song has; one that does not is a constant offset, said by the median over its bars.
  const std::vector<BeatOffset> offsets = beat_offsets(map, analysis->beats_s, downbeat_ms);
  std::map<long long, std::vector<double>> bars;
  for (const BeatOffset& o : offsets) bars[o.bar].push_back(o.ms);
  std::vector<std::pair<long long, double>> medians;
  for (const auto& [bar, ms] : bars) medians.emplace_back(bar, median(ms));
  for (std::size_t i = 0; i < medians.size();) {
    const double first = medians[i].second;
    if (std::abs(first) <= kSongBeatToleranceMs) {
      ++i;
      continue;
    }
    std::vector<double> run;
    std::size_t j = i;
    while (j < medians.size() && std::abs(medians[j].second) > kSongBeatToleranceMs &&
           (medians[j].second > 0) == (first > 0)) {
      run.push_back(medians[j].second);
      ++j;
    }
    if (run.size() < 2) {
      i = j;
      continue;
    }
    const long long from_bar = medians[i].first;
    const long long to_bar = medians[j - 1].first;
    std::vector<BeatOffset> points;
    for (const BeatOffset& o : offsets) {
      // A beat whose offset passed half a beat was counted to the next one: not on the line.
      if (o.bar >= from_bar && o.bar <= to_bar && (o.ms > 0) == (first > 0)) points.push_back(o);
    }
    const LineFit fit = fit_line(points);
    const double span = static_cast<double>(points.back().beat - points.front().beat);
    if (std::abs(fit.slope) * span > kSongBeatToleranceMs && fit.rms_line < fit.rms_flat / 2) {
      // The song's beat is the file's plus the slope; the stretch starts where the line
      // crosses zero, on the bar line nearest it.
      const double start_beat = std::max(0.0, -fit.intercept / fit.slope);
      const ExactMs start = map.time_of_beat(ExactMs(std::llround(start_beat))).value_or(ExactMs{});
      const double file_bpm = map.bpm_at(start);
      const double song_bpm = 60000 / (60000 / file_bpm + fit.slope);
      const long long bar = static_cast<long long>(std::llround(
                                map.bar_of_beat(ExactMs::from_double(start_beat)).value())) +
                            1;
      const double at_first = fit.intercept + fit.slope * double(points.front().beat);
      const double at_last = fit.intercept + fit.slope * double(points.back().beat);
      const std::string paste =
          bar <= 1 ? "tempo: " + tempo_text(song_bpm)
                   : fmt::format("- {{bar: {}, tempo: {}}}", bar, tempo_text(song_bpm));
      reporter.warning(
          song.at,
          fmt::format("{}the song runs at {:.1f} bpm; the file says {} (from bar {} its beats run "
                      "{} by {} ms, growing to {} ms)",
                      bar <= 1 ? "" : fmt::format("from bar {} ", bar), song_bpm,
                      fmt::format("{:g}", file_bpm), from_bar, fit.slope > 0 ? "ahead" : "behind",
                      std::llround(std::abs(at_first)), std::llround(std::abs(at_last))),
          Reporter::Note{song.at, bar <= 1 ? "paste '" + paste + "' into the 'music:' block"
                                           : "paste '" + paste + "' under 'changes:'"});
      return;  // the later bars follow from the wrong tempo
    }
    const double by = median(run);
    const std::string what =
        fmt::format("the file's beats run {} ms {} the song from bar {}",
                    std::llround(std::abs(by)), by > 0 ? "ahead of" : "behind", from_bar);
    if (from_bar == medians.front().first) {
      reporter.warning(song.at, what,
                       Reporter::Note{song.at, fmt::format("paste 'downbeat: {:.3f}s' into the "
                                                           "'music:' block",
                                                           (downbeat_ms + by) / 1000)});
    } else {
      reporter.warning(song.at, what);
    }
    i = j;
  }
}

}  // namespace seqc::compiler
