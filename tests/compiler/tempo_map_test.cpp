// The tempo map's musical-time arithmetic on maps built by hand: a time in any unit after an
// instant, where a bar and a beat of it fall, and how far an instant is off its bar line. At
// 120 bpm a beat is 500 ms and a 4/4 bar 2000 ms; at 60 bpm a beat is 1000 ms; at 110 bpm it is
// 60000/110 = 6000/11 ms. Bars and beats count from 0 (a musician's bar 1 beat 1 is bar 0 beat 0).
#include <gtest/gtest.h>

#include <optional>

#include "compiler/timeline/tempo_map.hpp"

namespace seqc::compiler {
namespace {

TEST(TempoMapAfter, EachUnitFromAnInstant) {
  const TempoMap map(120, 4);
  EXPECT_EQ(map.after(ExactMs(1000), ExactMs(250), TimeUnit::Milliseconds), ExactMs(1250));
  EXPECT_EQ(map.after(ExactMs(1000), ExactMs::from_double(1.5), TimeUnit::Seconds), ExactMs(2500));
  EXPECT_EQ(map.after(ExactMs(0), ExactMs(3), TimeUnit::Beats), ExactMs(1500));
  EXPECT_EQ(map.after(ExactMs(500), ExactMs(2), TimeUnit::Bars), ExactMs(4500));
}

TEST(TempoMapAfter, BeatsAndBarsAcrossATempoChange) {
  TempoMap map(120, 4);
  map.set_tempo(ExactMs(2000), 60);  // from bar 1 on, 1000 ms a beat
  // 1500 ms is beat 3: one beat of 500 ms to 2000, then one of 1000 ms.
  EXPECT_EQ(map.after(ExactMs(1500), ExactMs(2), TimeUnit::Beats), ExactMs(3000));
  // 1.5 bars are 6 beats: 4 of 500 ms to 2000, then 2 of 1000 ms.
  EXPECT_EQ(map.after(ExactMs(0), ExactMs::from_double(1.5), TimeUnit::Bars), ExactMs(4000));
  // Milliseconds and seconds do not care about the tempo.
  EXPECT_EQ(map.after(ExactMs(1500), ExactMs(1), TimeUnit::Seconds), ExactMs(2500));
}

TEST(TempoMapAfter, NoTempoNoBeatsButMillisecondsStill) {
  const TempoMap map(0, 4);
  EXPECT_EQ(map.after(ExactMs(0), ExactMs(1), TimeUnit::Beats), std::nullopt);
  EXPECT_EQ(map.after(ExactMs(0), ExactMs(1), TimeUnit::Bars), std::nullopt);
  EXPECT_EQ(map.after(ExactMs(10), ExactMs(5), TimeUnit::Milliseconds), ExactMs(15));
  // A tempo that stops at 1000 ms: one beat from 750 ms would run past it.
  TempoMap stopping(120, 4);
  stopping.set_tempo(ExactMs(1000), 0);
  EXPECT_EQ(stopping.after(ExactMs(250), ExactMs(1), TimeUnit::Beats), ExactMs(750));
  EXPECT_EQ(stopping.after(ExactMs(750), ExactMs(1), TimeUnit::Beats), std::nullopt);
}

TEST(TempoMapBars, BarsAndBeatsThroughTempoAndMeterChanges) {
  TempoMap map(120, 4);
  map.set_tempo(ExactMs(2000), 60);  // bar 1 on: 4000 ms a bar
  map.set_meter(ExactMs(6000), 3);   // bar 2 on: 3/4, 3000 ms a bar
  EXPECT_EQ(map.time_of_bar(ExactMs(0)), ExactMs(0));
  EXPECT_EQ(map.time_of_bar(ExactMs(1)), ExactMs(2000));
  EXPECT_EQ(map.time_of_bar(ExactMs(2)), ExactMs(6000));
  EXPECT_EQ(map.time_of_bar(ExactMs(3)), ExactMs(9000));
  // Bar 0 beat 1.5 (a musician's bar 1 beat 2.5): 1.5 x 500 ms.
  EXPECT_EQ(map.time_of_bar_beat(ExactMs(0), ExactMs::from_double(1.5)), ExactMs(750));
  // Bar 1 beat 2 (bar 2 beat 3): 2000 + 2 x 1000.
  EXPECT_EQ(map.time_of_bar_beat(ExactMs(1), ExactMs(2)), ExactMs(4000));
  // Bar 3 beat 1 (bar 4 beat 2): 9000 + 1000.
  EXPECT_EQ(map.time_of_bar_beat(ExactMs(3), ExactMs(1)), ExactMs(10000));
}

TEST(TempoMapBars, ExactAt110Bpm) {
  const TempoMap map(110, 4);
  // Bar 440 starts after 1760 beats: 1760 x 6000/11 = 960,000 ms, exactly.
  EXPECT_EQ(map.time_of_bar(ExactMs(440)), ExactMs(960000));
  // Beat 3 of bar 0: 18000/11 ms.
  EXPECT_EQ(map.time_of_bar_beat(ExactMs(0), ExactMs(3)), ExactMs::ratio(18000, 11));
}

TEST(TempoMapBars, NoneWhereNoMeterOrNoTempoCounts) {
  EXPECT_EQ(TempoMap(120, 0).time_of_bar(ExactMs(1)), std::nullopt);  // no meter
  EXPECT_EQ(TempoMap(0, 4).time_of_bar(ExactMs(1)), std::nullopt);    // no tempo
  // The tempo stops at 1000 ms, beat 2 of bar 0: beat 2 still falls there, beat 3 never.
  TempoMap stopping(120, 4);
  stopping.set_tempo(ExactMs(1000), 0);
  EXPECT_EQ(stopping.time_of_bar_beat(ExactMs(0), ExactMs(2)), ExactMs(1000));
  EXPECT_EQ(stopping.time_of_bar_beat(ExactMs(0), ExactMs(3)), std::nullopt);
}

TEST(TempoMapBarLine, HowFarIntoItsBar) {
  const TempoMap map(120, 4);
  EXPECT_EQ(map.off_bar_line(ExactMs(0)), std::nullopt);
  EXPECT_EQ(map.off_bar_line(ExactMs(4000)), std::nullopt);  // bar 2's line
  // 2750 ms is beat 5.5: bar 1 started on beat 4, so 1.5 beats into it.
  const auto off = map.off_bar_line(ExactMs(2750));
  ASSERT_TRUE(off.has_value());
  EXPECT_EQ(off->bar, 1);
  EXPECT_EQ(off->beats, ExactMs::from_double(1.5));
}

TEST(TempoMapBarLine, AfterAMeterChangeAndAt110Bpm) {
  TempoMap map(120, 4);
  map.set_meter(ExactMs(2000), 3);  // bar 1 on: 3/4
  // 3000 ms is beat 6: bar 1 (from beat 4) two beats in; 3500 ms is beat 7, bar 2's line.
  const auto off = map.off_bar_line(ExactMs(3000));
  ASSERT_TRUE(off.has_value());
  EXPECT_EQ(off->bar, 1);
  EXPECT_EQ(off->beats, ExactMs(2));
  EXPECT_EQ(map.off_bar_line(ExactMs(3500)), std::nullopt);
  // 3/4 at 110 bpm: 4 beats (24000/11 ms) are one beat into bar 1; 3 beats are its line.
  const TempoMap waltz(110, 3);
  const auto in_bar_1 = waltz.off_bar_line(ExactMs::ratio(24000, 11));
  ASSERT_TRUE(in_bar_1.has_value());
  EXPECT_EQ(in_bar_1->bar, 1);
  EXPECT_EQ(in_bar_1->beats, ExactMs(1));
  EXPECT_EQ(waltz.off_bar_line(ExactMs::ratio(18000, 11)), std::nullopt);
}

// Note values: 90 bpm in 3/4 is a quarter of 2000/3 ms (a bar 2000 ms); 6/8 after it keeps the
// eighth at 1000/3 ms (180 bpm), so its bar of six is 2000 ms too.
TEST(TempoMapNotes, AMeterChangeKeepsEachNotesLength) {
  TempoMap map(90, 3, 4);
  map.set_meter(ExactMs(4000), 6, 8);  // bar 3
  EXPECT_EQ(map.bpm_at(ExactMs(4000)), 180);
  EXPECT_EQ(map.beat_ms_at(ExactMs(4000)), ExactMs::ratio(1000, 3));
  EXPECT_EQ(map.time_of_bar(ExactMs(2)), ExactMs(4000));
  EXPECT_EQ(map.time_of_bar(ExactMs(3)), ExactMs(6000));
  EXPECT_EQ(map.time_of_bar_beat(ExactMs(3), ExactMs(3)), ExactMs(7000));
  // Back to 3/4: the quarter is 2000/3 ms again.
  map.set_meter(ExactMs(6000), 3, 4);
  EXPECT_EQ(map.beat_ms_at(ExactMs(6000)), ExactMs::ratio(2000, 3));
  EXPECT_EQ(map.time_of_bar(ExactMs(4)), ExactMs(8000));
}

TEST(TempoMapNotes, ATempoWithItsNote) {
  // A dotted quarter (3/8) at 60 lasts 1000 ms: in 6/8 an eighth is a third of it.
  EXPECT_EQ(beat_ms(Tempo{60, 3, 8}, 8), ExactMs::ratio(1000, 3));
  // In 4/4 a quarter is two thirds of it.
  EXPECT_EQ(beat_ms(Tempo{60, 3, 8}, 4), ExactMs::ratio(2000, 3));
  // A half at 60 is 1000 ms: a quarter 500 ms. A plain number counts the meter's beat.
  EXPECT_EQ(beat_ms(Tempo{60, 1, 2}, 4), ExactMs(500));
  EXPECT_EQ(beat_ms(Tempo{120, 0, 0}, 8), ExactMs(500));
  TempoMap map(Tempo{60, 3, 8}, TimeSignature{6, 8});
  EXPECT_EQ(map.bpm_at(ExactMs(0)), 180);
  EXPECT_EQ(map.time_of_bar(ExactMs(1)), ExactMs(2000));
  map.set_tempo(ExactMs(2000), Tempo{30, 3, 8});  // a dotted quarter of 2 s
  EXPECT_EQ(map.time_of_bar(ExactMs(2)), ExactMs(6000));
}

TEST(TempoMapNotes, ThirdsAndSixthsAreExact) {
  const TempoMap map(120, 4);
  const ExactMs third = ExactMs::ratio(1, 3);
  ExactMs t(0);
  for (int i = 0; i < 12; ++i) t = *map.after(t, third, TimeUnit::Beats);
  EXPECT_EQ(t, ExactMs(2000));
  ExactMs u(0);
  for (int i = 0; i < 6; ++i) u = *map.after(u, ExactMs::ratio(1, 6), TimeUnit::Bars);
  EXPECT_EQ(u, ExactMs(2000));
  // One sixth of a bar is 1000/3 ms, 333.33.. ms.
  EXPECT_EQ(map.after(ExactMs(0), ExactMs::ratio(1, 6), TimeUnit::Bars), ExactMs::ratio(1000, 3));
}

TEST(TempoMapNotes, AWrittenFractionIsExact) {
  TimeValue third;
  third.amount = 1.0 / 3;
  third.numerator = 1;
  third.denominator = 3;
  EXPECT_EQ(exact_amount(third), ExactMs::ratio(1, 3));
  TimeValue decimal;
  decimal.amount = 1.5;
  EXPECT_EQ(exact_amount(decimal), ExactMs::ratio(3, 2));
}

}  // namespace
}  // namespace seqc::compiler
