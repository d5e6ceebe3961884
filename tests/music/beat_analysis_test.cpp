// The beat analysis on generated songs: every expected tempo, downbeat and change comes from the
// song's own recipe (tests/music/song_generator.hpp), with the tolerance stated at each check.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "compiler/music/beat_analysis.hpp"
#include "compiler/music/beat_tracking.hpp"
#include "compiler/music/fft.hpp"
#include "tests/music/song_generator.hpp"

namespace seqc::music {
namespace {

using testing::make_clicks;
using testing::make_noise;
using testing::make_song;
using testing::Song;
using testing::SongSpec;

BeatAnalysis analyze(const Song& song, BeatOptions options = {}) {
  auto result = analyze_beats(song.samples, song.sample_rate, options);
  EXPECT_TRUE(result.ok()) << (result.ok() ? "" : result.error().message);
  return result.ok() ? *result : BeatAnalysis{};
}

// The tempo and downbeat targets of docs/music.md: 0.05 BPM, 5 ms.
void expect_map(const BeatAnalysis& a, double tempo, double downbeat_s, int meter) {
  ASSERT_FALSE(a.map.stretches.empty());
  EXPECT_NEAR(a.map.stretches.front().tempo, tempo, 0.05);
  EXPECT_NEAR(a.map.downbeat_s(), downbeat_s, 0.005);
  EXPECT_EQ(a.map.meter.beats, meter);
  EXPECT_GE(a.confidence, 0.9);
}

TEST(Fft, MatchesTheDefinitionOfTheDft) {
  // X[k] = sum x[n] e^{-2 pi i k n / N}, computed term by term here.
  const std::size_t n = 16;
  std::vector<std::complex<double>> x(n);
  for (std::size_t i = 0; i < n; ++i) x[i] = {std::sin(0.7 * double(i)) + 0.1 * double(i), 0};
  std::vector<std::complex<double>> expected(n);
  for (std::size_t k = 0; k < n; ++k) {
    for (std::size_t j = 0; j < n; ++j) {
      const double angle = -2 * std::numbers::pi * double(k * j) / double(n);
      expected[k] += x[j] * std::complex<double>(std::cos(angle), std::sin(angle));
    }
  }
  Fft fft(n);
  fft.forward(x);
  for (std::size_t k = 0; k < n; ++k) {
    EXPECT_NEAR(x[k].real(), expected[k].real(), 1e-9) << k;
    EXPECT_NEAR(x[k].imag(), expected[k].imag(), 1e-9) << k;
  }
}

TEST(SteadyGrid, OneGridThroughAPassageWhereTheOffBeatsAreLouder) {
  // An envelope with a pulse every 30.37 frames from frame 7.2, and 20 beats in the middle
  // where the off-beats are twice as loud and the beats faint: the grid stays on the beats.
  const double period = 30.37, phase = 7.2;
  std::vector<double> flux(3000, 0.0);
  for (int k = 0; phase + k * period < 2990; ++k) {
    const double beat = phase + k * period;
    const bool passage = beat > 1000 && beat < 1600;
    flux[static_cast<std::size_t>(std::lround(beat))] = passage ? 0.3 : 1.0;
    if (passage) flux[static_cast<std::size_t>(std::lround(beat + period / 2))] = 2.0;
  }
  // Laid over the frames from 100 on: the phase is still counted from frame 0.
  const SteadyGrid grid = steady_grid(flux, 30.0, 100, flux.size() - 1);
  // Each beat takes the envelope's largest value within a frame: over the 98 beats the last
  // one may land up to a frame and a half from the true one.
  EXPECT_NEAR(grid.period, period, 1.5 / 98);
  EXPECT_NEAR(grid.phase, phase, 1.0);
}

TEST(BeatAnalysis, ClicksGiveTheirTempoAndFirstAccentedClick) {
  // 120 BPM, accented click every 4th, first click at 0.5 s.
  const Song song = make_clicks(120, 4, 0.5, 30, 22050);
  expect_map(analyze(song), 120, 0.5, 4);
}

TEST(BeatAnalysis, DrumPatternWithJitterAndNoise) {
  SongSpec spec;
  spec.tempo = 128;
  spec.lead_in_s = 0.75;
  spec.jitter_ms = 3;
  spec.noise = 0.01;
  spec.sample_rate = 44100;
  const BeatAnalysis a = analyze(make_song(spec));
  expect_map(a, 128, 0.75, 4);
  EXPECT_EQ(a.map.stretches.size(), 1u);
}

TEST(BeatAnalysis, WaltzIsThreeFour) {
  SongSpec spec;
  spec.tempo = 96;
  spec.meter = 3;
  spec.lead_in_s = 1.2;
  spec.bars = 32;
  spec.jitter_ms = 2;
  const BeatAnalysis a = analyze(make_song(spec));
  expect_map(a, 96, 1.2, 3);
  EXPECT_TRUE(a.meter_detected);
}

TEST(BeatAnalysis, TwoAndSixBeatsToTheBarAreFound) {
  // A march: kick and bass on 1, snare on 2, a new bass note every two beats.
  SongSpec march;
  march.tempo = 112;
  march.meter = 2;
  march.bars = 40;
  const BeatAnalysis two = analyze(make_song(march));
  EXPECT_EQ(two.map.meter, (Meter{2, 4}));
  EXPECT_NEAR(two.map.downbeat_s(), 0.75, 0.005);
  // A jig counted in eighths: kick and bass on 1 of 6, soft snares on the other five.
  SongSpec jig;
  jig.tempo = 150;
  jig.meter = 6;
  jig.bars = 16;
  const BeatAnalysis six = analyze(make_song(jig));
  EXPECT_EQ(six.map.meter, (Meter{6, 8}));
  EXPECT_NEAR(six.map.downbeat_s(), 0.75, 0.005);
  EXPECT_NEAR(six.map.stretches.front().tempo, 150, 0.05);
}

TEST(BeatAnalysis, AStrongThirdBeatStillMakesBarsOfFour) {
  // Kicks as loud on 3 as on 1; only the bass note (a new one each bar, on 1) marks the bar.
  SongSpec spec;
  spec.tempo = 124;
  spec.third_kick = 1.0;
  spec.bars = 32;
  const BeatAnalysis a = analyze(make_song(spec));
  EXPECT_EQ(a.map.meter, (Meter{4, 4}));
  EXPECT_NEAR(a.map.downbeat_s(), 0.75, 0.005);
}

TEST(BeatAnalysis, SwungEighthsKeepTheBeat) {
  SongSpec spec;
  spec.tempo = 100;
  spec.swing = 1.0 / 3;  // the off-beat at 2/3 of the beat
  spec.lead_in_s = 0.3;
  spec.jitter_ms = 2;
  expect_map(analyze(make_song(spec)), 100, 0.3, 4);
}

TEST(BeatAnalysis, QuietIntroCountsFromItsFirstBar) {
  SongSpec spec;
  spec.tempo = 110;
  spec.quiet_bars = 4;  // -20 dB
  spec.lead_in_s = 2.0;
  spec.jitter_ms = 2;
  expect_map(analyze(make_song(spec)), 110, 2.0, 4);
}

TEST(BeatAnalysis, UpbeatComesBeforeBarOne) {
  // Three beats of snare before bar 1: the downbeat is where the kick and bass come in, 1.5 s
  // after the first upbeat at 120 BPM.
  SongSpec spec;
  spec.tempo = 120;
  spec.pickup = 3;
  spec.lead_in_s = 2.0;
  spec.jitter_ms = 1;
  expect_map(analyze(make_song(spec)), 120, 2.0, 4);
}

TEST(BeatAnalysis, LateHitsAtTheEndAreLeftOut) {
  // 150 BPM (0.4 s), 24 bars = 96 beats, 1 ms jitter; the last 3 beats 40 ms late (a drummer
  // rushing the ending). Fitted with the rest, they would tilt the line: slope change
  // 0.040 s * (45.5 + 46.5 + 47.5) / (96^3 / 12) = 7.6e-5 s per beat, 60 * 7.6e-5 / 0.4^2 =
  // 0.028 BPM. Left out, the tempo's standard error is 60 * (0.001 / sqrt(73728)) / 0.16 =
  // 0.0014 BPM: 0.01 allows 7 of those and catches the tilt.
  SongSpec spec;
  spec.tempo = 150;
  spec.bars = 24;
  spec.jitter_ms = 1;
  spec.late_beat = 24 * 4 - 3;
  spec.late_count = 3;
  spec.late_ms = 40;
  const BeatAnalysis a = analyze(make_song(spec));
  expect_map(a, 150, 0.75, 4);
  ASSERT_EQ(a.map.stretches.size(), 1u);
  EXPECT_NEAR(a.map.stretches.front().tempo, 150, 0.01);
}

TEST(BeatAnalysis, HitsWithoutAPulseHaveNoSteadyBeat) {
  // 40 snare hits at random times in 20 s.
  const Song hits = testing::make_random_hits(20, 40, 22050, 11);
  auto result = analyze_beats(hits.samples, hits.sample_rate, {});
  ASSERT_FALSE(result.ok()) << result->map.stretches.front().tempo << " " << result->confidence;
  EXPECT_NE(result.error().message.find("no steady beat"), std::string::npos)
      << result.error().message;
}

TEST(BeatAnalysis, TempoChangeFallsOnItsBar) {
  SongSpec spec;
  spec.tempo = 128;
  spec.bars = 32;
  spec.change_bar = 17;
  spec.change_tempo = 132;
  spec.jitter_ms = 2;
  const BeatAnalysis a = analyze(make_song(spec));
  expect_map(a, 128, 0.75, 4);
  ASSERT_EQ(a.map.stretches.size(), 2u);
  EXPECT_EQ(a.map.stretches[1].bar, 17);
  EXPECT_NEAR(a.map.stretches[1].tempo, 132, 0.05);
  // Bar 17 starts after 16 bars of 4 beats at 128 BPM: 0.75 + 64 * 60/128 = 30.75 s.
  EXPECT_NEAR(a.map.stretches[1].start_s, 30.75, 0.005);
}

TEST(BeatAnalysis, ALargeTempoChangeIsFollowed) {
  // 120 BPM for 16 bars (0.75 + 64 * 0.5 = 32.75 s), then 96 BPM: 20% slower.
  SongSpec spec;
  spec.tempo = 120;
  spec.bars = 32;
  spec.change_bar = 17;
  spec.change_tempo = 96;
  const BeatAnalysis a = analyze(make_song(spec));
  expect_map(a, 120, 0.75, 4);
  ASSERT_EQ(a.map.stretches.size(), 2u);
  EXPECT_EQ(a.map.stretches[1].bar, 17);
  EXPECT_NEAR(a.map.stretches[1].tempo, 96, 0.05);
  EXPECT_NEAR(a.map.stretches[1].start_s, 32.75, 0.005);
}

TEST(BeatAnalysis, ATempoThatDriftsIsFollowedAndTheMapStaysOnTheBeats) {
  // A band speeding up by a quarter of a BPM every bar, 100 to 111.75 BPM over 48 bars: no
  // single tempo fits (bar 48 would be off by seconds), and the map read as a chain (each
  // stretch starting where the one before ends at its printed tempo) must stay on the beats.
  SongSpec spec;
  spec.tempo = 100;
  spec.drift_per_bar = 0.25;
  spec.bars = 48;
  spec.jitter_ms = 2;
  const Song song = make_song(spec);
  const BeatAnalysis a = analyze(song);
  ASSERT_GE(a.map.stretches.size(), 3u);
  // 10 ms: the first stretch's line runs through a tempo that is already rising.
  EXPECT_NEAR(a.map.downbeat_s(), 0.75, 0.010);
  // Chained here from the printed text, the way a choreography's `changes:` are read.
  const std::string block = music_block("s.wav", a.map);
  std::vector<double> map_beats;
  double t = 0.75;
  for (std::size_t i = 0; i < a.map.stretches.size(); ++i) {
    const TempoStretch& s = a.map.stretches[i];
    const double shown = std::stod(tempo_text(s.tempo, s.decimals));
    EXPECT_NE(block.find(tempo_text(s.tempo, s.decimals)), std::string::npos);
    const int end_bar = i + 1 < a.map.stretches.size() ? a.map.stretches[i + 1].bar : 49;
    for (int beat = 0; beat < (end_bar - s.bar) * 4; ++beat) {
      map_beats.push_back(t);
      t += 60.0 / shown;
    }
  }
  ASSERT_EQ(map_beats.size(), song.beats_s.size());
  double worst = 0;
  for (std::size_t i = 0; i < map_beats.size(); ++i) {
    worst = std::max(worst, std::abs(map_beats[i] - song.beats_s[i]));
  }
  // Within 25 ms everywhere: the tolerance the analysis keeps a stretch to.
  EXPECT_LT(worst, 0.025) << block;
}

TEST(BeatAnalysis, ABreakdownOnTheOffBeatsKeepsTheSongsGrid) {
  // 16 bars at 140 BPM, then 12 bars where the off-beats are loud and the beats a soft hi-hat,
  // then 16 bars as before: played to a click, the beats stay where they were; a tracker that
  // follows the loudest onsets slips half a beat there and back.
  SongSpec spec;
  spec.tempo = 140;
  spec.bars = 38;
  spec.skank_bar = 17;
  spec.skank_bars = 12;
  spec.jitter_ms = 2;
  const Song song = make_song(spec);
  const BeatAnalysis a = analyze(song);
  expect_map(a, 140, 0.75, 4);
  EXPECT_EQ(a.map.stretches.size(), 1u);
  // Every beat listed is one of the song's beats (within 20 ms), none half a beat off.
  for (double t : a.beats_s) {
    const auto near =
        std::min_element(song.beats_s.begin(), song.beats_s.end(),
                         [&](double x, double y) { return std::abs(x - t) < std::abs(y - t); });
    EXPECT_LT(std::abs(*near - t), 0.020) << t;
  }
}

TEST(BeatAnalysis, TempoHintPicksTheMetricalLevel) {
  SongSpec spec;
  spec.tempo = 75;
  spec.lead_in_s = 0.5;
  const Song song = make_song(spec);
  expect_map(analyze(song), 75, 0.5, 4);
  BeatOptions fast;
  fast.tempo_hint = 150;
  const BeatAnalysis doubled = analyze(song, fast);
  ASSERT_FALSE(doubled.map.stretches.empty());
  EXPECT_NEAR(doubled.map.stretches.front().tempo, 150, 0.1);
  // Half the tempo of a 128 BPM song is 64, not a level two thirds of the beat's tempo that a
  // grid of three beats (as strongly marked as every beat) would suggest.
  SongSpec quick;
  quick.tempo = 128;
  BeatOptions slow;
  slow.tempo_hint = 64;
  const BeatAnalysis halved = analyze(make_song(quick), slow);
  ASSERT_FALSE(halved.map.stretches.empty());
  EXPECT_NEAR(halved.map.stretches.front().tempo, 64, 0.05);
}

TEST(BeatAnalysis, BeatListGivesEachBeatsTimeAndPlaceInTheBar) {
  // Clicks at 120 BPM from 0.5 s, every 4th accented: beats every 0.5 s, bar 1 at 0.5 s.
  const BeatAnalysis a = analyze(make_clicks(120, 4, 0.5, 12, 22050));
  const std::string list = beat_list(a);
  EXPECT_EQ(list.substr(0, 40), "0.500\t1\n1.000\t2\n1.500\t3\n2.000\t4\n2.500\t1\n") << list;
  EXPECT_EQ(std::count(list.begin(), list.end(), '\n'), static_cast<long>(a.beats_s.size()));
}

TEST(BeatAnalysis, GivenMeterIsKept) {
  SongSpec spec;
  spec.tempo = 120;
  BeatOptions options;
  options.meter = Meter{3, 8};
  const BeatAnalysis a = analyze(make_song(spec), options);
  EXPECT_EQ(a.map.meter, (Meter{3, 8}));
  EXPECT_FALSE(a.meter_detected);
}

TEST(BeatAnalysis, NoiseHasNoSteadyBeat) {
  const Song noise = make_noise(20, 0.1, 22050, 7);
  auto result = analyze_beats(noise.samples, noise.sample_rate, {});
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.error().message.find("no steady beat"), std::string::npos)
      << result.error().message;
}

TEST(BeatAnalysis, SilenceHasNoSteadyBeat) {
  const std::vector<float> silence(22050 * 10, 0.0f);
  EXPECT_FALSE(analyze_beats(silence, 22050, {}).ok());
}

TEST(BeatAnalysis, TooShortIsSaid) {
  const Song song = make_clicks(120, 4, 0.1, 3, 22050);
  auto result = analyze_beats(song.samples, song.sample_rate, {});
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.error().message, "too short to find a beat (3.0 s; at least 6 s)");
}

}  // namespace
}  // namespace seqc::music
