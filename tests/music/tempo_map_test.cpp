// The music block's text and the beats of a tempo map, on maps written by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "compiler/music/click_track.hpp"
#include "compiler/music/tempo_map.hpp"

namespace seqc::music {
namespace {

TEST(TempoMapText, OneStretch) {
  TempoMap map{{4, 4}, {{1, 0.75, 127.9612, 2}}};
  EXPECT_EQ(music_block("neon-pulse.ogg", map),
            "music:\n"
            "  file: neon-pulse.ogg\n"
            "  downbeat: 0.750s\n"
            "  tempo: 127.96\n"
            "  meter: 4/4\n");
}

TEST(TempoMapText, ChangesByBarAndQuotedFileNames) {
  TempoMap map{{3, 4}, {{1, 1.0004, 128.0004, 3}, {33, 61.0, 131.9996, 2}}};
  EXPECT_EQ(music_block("my song: live #2.wav", map),
            "music:\n"
            "  file: \"my song: live #2.wav\"\n"
            "  downbeat: 1.000s\n"
            "  tempo: 128\n"
            "  meter: 3/4\n"
            "  changes:\n"
            "    - {bar: 33, tempo: 132}\n");
}

TEST(TempoMapText, TempoDigits) {
  EXPECT_EQ(tempo_text(127.96, 2), "127.96");
  EXPECT_EQ(tempo_text(127.5, 3), "127.5");
  EXPECT_EQ(tempo_text(127.6, 0), "128");
  EXPECT_EQ(tempo_text(120.0001, 3), "120");
}

TEST(TempoMapBeats, BeatsBeforeBarOneAndAcrossAChange) {
  // 120 BPM (0.5 s) from bar 1 at 1.2 s; 2 bars of 2/4; then 60 BPM from bar 3 at 3.2 s.
  TempoMap map{{2, 4}, {{1, 1.2, 120, 0}, {3, 3.2, 60, 0}}};
  const std::vector<MapBeat> beats = map_beats(map, 0.0, 5.5);
  // 0.2 and 0.7 (before bar 1; 0.7 is beat 2 of bar 0, 0.2 its beat 1), 1.2 1.7 2.2 2.7,
  // 3.2 4.2 5.2.
  const std::vector<double> times = {0.2, 0.7, 1.2, 1.7, 2.2, 2.7, 3.2, 4.2, 5.2};
  const std::vector<bool> down = {true, false, true, false, true, false, true, false, true};
  ASSERT_EQ(beats.size(), times.size());
  for (std::size_t i = 0; i < times.size(); ++i) {
    EXPECT_NEAR(beats[i].time_s, times[i], 1e-9) << i;
    EXPECT_EQ(beats[i].downbeat, down[i]) << i;
  }
}

TEST(ClickTrack, ClicksStartOnTheBeatsAndBarOneIsLouder) {
  // 8 kHz keeps the sample arithmetic by hand: 60 BPM from 0.5 s (sample 4000), 2/4, 3 s of
  // silence, so clicks at 0.5 (bar 1), 1.5, 2.5 (bar 2) s.
  TempoMap map{{2, 4}, {{1, 0.5, 60, 0}}};
  const std::vector<float> silence(8000 * 3, 0.0f);
  const std::vector<float> clicks = mix_click_track(silence, 8000, map);
  ASSERT_EQ(clicks.size(), silence.size());
  auto peak = [&](double at_s) {
    float p = 0;
    const auto start = static_cast<std::size_t>(at_s * 8000);
    for (std::size_t k = start; k < start + 80; ++k) p = std::max(p, std::abs(clicks[k]));
    return p;
  };
  auto quiet = [&](double at_s) {
    const auto start = static_cast<std::size_t>(at_s * 8000);
    for (std::size_t k = start; k < start + 400; ++k) {
      if (clicks[k] != 0.0f) return false;
    }
    return true;
  };
  EXPECT_GT(peak(0.5), 0.3f);  // bar 1: level 0.5
  EXPECT_GT(peak(1.5), 0.15f);
  EXPECT_LT(peak(1.5), 0.3f);  // beat 2: level 0.3
  EXPECT_GT(peak(2.5), 0.3f);  // bar 2
  EXPECT_TRUE(quiet(0.05));    // nothing between clicks (a click lasts 30 ms)
  EXPECT_TRUE(quiet(0.9));
  EXPECT_EQ(clicks[4000], 0.0f);  // a click starts at zero phase, on its sample
  EXPECT_NE(clicks[4001], 0.0f);
  EXPECT_EQ(clicks[3999], 0.0f);
}

TEST(TempoMapText, MeterText) {
  EXPECT_EQ(parse_meter("3/4"), (music::Meter{3, 4}));
  EXPECT_EQ(parse_meter("6/8"), (music::Meter{6, 8}));
  EXPECT_EQ(parse_meter("12/16"), (music::Meter{12, 16}));
  EXPECT_EQ(parse_meter("3"), std::nullopt);
  EXPECT_EQ(parse_meter("3/5"), std::nullopt);
  EXPECT_EQ(parse_meter("0/4"), std::nullopt);
  EXPECT_EQ(parse_meter("17/4"), std::nullopt);
  EXPECT_EQ(parse_meter("3/4x"), std::nullopt);
}

}  // namespace
}  // namespace seqc::music
