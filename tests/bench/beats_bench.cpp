// beats_bench: how fast and how exactly `seqc beats` finds a song's tempo map.
//
// Speed: analyze_beats on a 4-minute generated song (44.1 kHz, 128 BPM, 4/4, jitter and noise),
// best of three runs, as a multiple of real time. Target >= 100x.
//
// Accuracy: 24 generated songs (tests/music/song_generator.hpp) of varied style: tempos from 70
// to 180 BPM (not whole numbers), 4/4 and 3/4, swung eighths, quiet intros (-20 dB), lead-ins
// of noise, 1-4 ms timing jitter, three sample rates, and tempo changes at bar 17. For each:
//   tempo error     |fitted - generated| of every stretch, BPM. Target <= 0.05.
//   downbeat error  |printed downbeat - generated bar 1 beat 1|, ms. Target <= 5.
//   changes         the stretches found against the ones generated (bar and count).
// No tempo hint and no meter are given: the metrical level and meter are found too.
//
// Usage: beats_bench [--quick]   (--quick: a 30 s speed song and 6 short songs, for ctest)
// Exit 1 when an accuracy target is missed; timings are printed, never judged.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "compiler/music/beat_analysis.hpp"
#include "tests/music/song_generator.hpp"

using seqc::music::analyze_beats;
using seqc::testing::make_song;
using seqc::testing::Song;
using seqc::testing::SongSpec;

namespace {

std::vector<SongSpec> songs(bool quick) {
  std::vector<SongSpec> out;
  const int count = quick ? 6 : 24;
  const double rates[] = {22050, 44100, 48000};
  for (int i = 0; i < count; ++i) {
    SongSpec s;
    s.tempo = 70.0 + 110.0 * i / (count - 1) + 0.37 * (i % 3);  // 70 .. 180.7
    s.meter = i % 4 == 1 ? 3 : 4;
    s.swing = i % 5 == 2 ? 1.0 / 3 : 0.0;
    s.quiet_bars = i % 6 == 3 ? 4 : 0;
    s.lead_in_s = 0.2 + 0.37 * (i % 7);
    s.jitter_ms = 1.0 + (i % 4);
    s.noise = i % 3 == 0 ? 0.01 : 0.002;
    s.sample_rate = rates[i % 3];
    s.bars = quick ? 16 : 32;
    if (i % 6 == 4) {
      s.change_bar = quick ? 9 : 17;
      s.change_tempo = s.tempo * (i % 12 == 4 ? 1.06 : 0.93);
    }
    s.seed = 100u + static_cast<unsigned>(i);
    out.push_back(s);
  }
  return out;
}

std::string style(const SongSpec& s) {
  std::string text = std::to_string(s.meter) + "/4";
  if (s.swing > 0) text += " swing";
  if (s.quiet_bars > 0) text += " quiet-intro";
  if (s.change_bar) text += " change";
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--quick") {
      quick = true;
    } else {
      std::fprintf(stderr, "usage: beats_bench [--quick]\n");
      return 2;
    }
  }

  // Speed.
  SongSpec long_song;
  long_song.sample_rate = 44100;
  long_song.tempo = 128;
  long_song.jitter_ms = 2;
  long_song.noise = 0.005;
  long_song.bars = quick ? 16 : 128;  // 128 bars at 128 BPM: 4 minutes
  const Song song = make_song(long_song);
  double best_s = 1e9;
  for (int run = 0; run < 3; ++run) {
    const auto start = std::chrono::steady_clock::now();
    auto result = analyze_beats(song.samples, song.sample_rate, {});
    const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
    if (!result) {
      std::printf("speed song: %s\n", result.error().message.c_str());
      return 1;
    }
    best_s = std::min(best_s, took.count());
  }
  std::printf(
      "speed: %.1f s of 44.1 kHz audio analysed in %.3f s: %.0fx real time "
      "(target >= 100x)\n\n",
      song.duration_s(), best_s, song.duration_s() / best_s);

  // Accuracy.
  std::printf("%-3s %-8s %-22s %6s %6s %11s %12s %8s %s\n", "#", "BPM", "style", "rate", "secs",
              "tempo err", "downbeat err", "stretches", "");
  double worst_tempo = 0, worst_downbeat = 0;
  int missed = 0;
  const std::vector<SongSpec> specs = songs(quick);
  for (std::size_t i = 0; i < specs.size(); ++i) {
    const SongSpec& s = specs[i];
    const Song g = make_song(s);
    auto result = analyze_beats(g.samples, g.sample_rate, {});
    if (!result) {
      std::printf("%-3zu %-8.2f %-22s %s\n", i, s.tempo, style(s).c_str(),
                  result.error().message.c_str());
      ++missed;
      continue;
    }
    const auto& map = result->map;
    double tempo_err = std::abs(map.stretches.front().tempo - s.tempo);
    const std::size_t want = s.change_bar ? 2 : 1;
    bool ok = map.stretches.size() == want && map.meter.beats == s.meter;
    if (ok && s.change_bar) {
      ok = map.stretches[1].bar == *s.change_bar;
      tempo_err = std::max(tempo_err, std::abs(map.stretches[1].tempo - s.change_tempo));
    }
    const double downbeat_err = std::abs(map.downbeat_s() - g.downbeat_s) * 1000;
    ok = ok && tempo_err <= 0.05 && downbeat_err <= 5;
    if (!ok) ++missed;
    worst_tempo = std::max(worst_tempo, tempo_err);
    worst_downbeat = std::max(worst_downbeat, downbeat_err);
    std::string found = std::to_string(map.stretches.size());
    if (map.stretches.size() > 1) found += " (bar " + std::to_string(map.stretches[1].bar) + ")";
    std::printf("%-3zu %-8.2f %-22s %6.0f %6.1f %8.4f BPM %9.2f ms %9s %s\n", i, s.tempo,
                (style(s) + (map.meter.beats != s.meter ? " (meter!)" : "")).c_str(), s.sample_rate,
                g.duration_s(), tempo_err, downbeat_err, found.c_str(), ok ? "ok" : "MISSED");
  }
  std::printf(
      "\n%zu songs: worst tempo error %.4f BPM (target <= 0.05), worst downbeat error "
      "%.2f ms (target <= 5), %d missed\n",
      specs.size(), worst_tempo, worst_downbeat, missed);
  return missed == 0 ? 0 : 1;
}
