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

// Per bar (counted from 1) of `map`, how much later than the file's beat each detected beat
// falls (ms; the song's beats in `beats_s`, audio time, with bar 1 beat 1 at `downbeat_ms`).
std::map<long long, std::vector<double>> offsets_by_bar(const TempoMap& map,
                                                        const std::vector<double>& beats_s,
                                                        double downbeat_ms) {
  std::map<long long, std::vector<double>> bars;
  for (double b : beats_s) {
    const double t = b * 1000 - downbeat_ms;
    if (t < 0) continue;  // a pickup before bar 1: the file has no beats there
    const double beat = map.beat_at(ExactMs::from_double(t)).value();
    const auto k = static_cast<std::int64_t>(std::llround(beat));
    const std::optional<ExactMs> planned = map.time_of_beat(ExactMs(k));
    if (!planned) continue;
    const auto bar = static_cast<long long>(std::floor(map.bar_of_beat(ExactMs(k)).value())) + 1;
    bars[bar].push_back(t - planned->value());
  }
  return bars;
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
  options.meter = music::Meter{song.beats_per_bar, 4};
  options.tempo_hint = song.bpm;
  const Result<music::BeatAnalysis> analysis =
      music::analyze_beats(std::span<const float>(audio->samples), audio->sample_rate, options);
  if (!analysis) {
    reporter.warning(song.file_at,
                     "cannot check the tempo map against the song: " + analysis.error().message);
    return;
  }
  // A bar disagrees when the median of its beats' offsets does (one stray beat does not make
  // it); a disagreement is reported once, from its first bar, by the median over its bars, and
  // only when it lasts two bars or more (a lone bar is the tracker's doubt, not the map's).
  const auto bars = offsets_by_bar(map, analysis->beats_s, downbeat_ms);
  std::vector<std::pair<long long, double>> medians;
  for (const auto& [bar, offsets] : bars) medians.emplace_back(bar, median(offsets));
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
    if (run.size() >= 2) {
      const double by = median(run);
      reporter.warning(song.at, fmt::format("from bar {} the file's beats run {} ms {} the song",
                                            medians[i].first, std::llround(std::abs(by)),
                                            by > 0 ? "ahead of" : "behind"));
    }
    i = j;
  }
}

}  // namespace seqc::compiler
