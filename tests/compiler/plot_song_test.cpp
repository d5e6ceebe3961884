// The song lane of `seqc plot` (compiler/formats/plot_song.hpp): the waveform's bars and the
// beats' ticks land where the `music:` downbeat and the plot's time axis put them. Positions
// are worked out here from the layout the header and plot_axes.hpp give: the lanes run from
// x = 150 to 1100 - 24 = 1076, 926 whole pixel columns, and a lane is 72 high.
#include <gtest/gtest.h>

#include <string>

#include "compiler/formats/plot_song.hpp"
#include "compiler/formats/plot_svg.hpp"
#include "tests/compiler/lang_test_util.hpp"

namespace seqc::compiler {
namespace {

using testing::compile_text;
using testing::program_of;

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// 5 s of silence at 1000 samples/s with one full-scale click at 1.5 s of audio. The downbeat is
// at 0.5 s, so the click is at 1000 ms of the sequence: on a 0-4000 ms window a column is
// 4000 / 926 = 4.3197 ms, and 1000 ms falls in column 231 (997.8-1002.2 ms), whose samples are
// 1497.8-1502.2: the click's column. Its bar is at x = 150 + 231 + 0.5 and fills the lane
// (peak 1): from y0 = 100 to 172.
compiler::PlotSong click_song() {
  compiler::PlotSong song;
  song.label = "click.wav";
  song.sample_rate = 1000;
  song.samples.assign(5000, 0.0f);
  song.samples[1500] = -1.0f;  // a peak is a magnitude
  song.downbeat_s = 0.5;
  // 1.5 s -> 1000 ms (x = 150 + 1000 / 4000 x 926 = 381.5); 5 s -> 4500 ms and 0.2 s -> -300 ms
  // fall outside the window.
  song.beats_s = {0.2, 1.5, 5.0};
  return song;
}

TEST(PlotSong, TheClickAndItsBeatLandOnTheSequencesTimeAxis) {
  const compiler::plot::Frame f{0, 4000};
  const std::string lane = compiler::plot::song_lane(click_song(), f, 100);
  EXPECT_NE(lane.find("d=\"M381.5 100V172\""), std::string::npos) << lane;
  EXPECT_EQ(count(lane, "class=\"beat\""), 1u) << lane;
  EXPECT_NE(lane.find("x1=\"381.5\" y1=\"100\" x2=\"381.5\" y2=\"118\""), std::string::npos)
      << lane;
  EXPECT_NE(lane.find(">click.wav</text>"), std::string::npos);
}

TEST(PlotSong, HalfAPeakIsHalfTheLaneAndSilenceDrawsNothing) {
  compiler::PlotSong song = click_song();
  song.samples[1500] = 0.5f;  // 0.5 x 72 = 36 high, about the middle 136
  const std::string half = compiler::plot::song_lane(song, {0, 4000}, 100);
  EXPECT_NE(half.find("d=\"M381.5 118V154\""), std::string::npos) << half;
  song.samples[1500] = 0.0f;
  const std::string silent = compiler::plot::song_lane(song, {0, 4000}, 100);
  EXPECT_EQ(silent.find("class=\"waveform\""), std::string::npos) << silent;
}

TEST(PlotSong, ThePlotGrowsALaneUnderTheServosOnlyWithASong) {
  auto out = compile_text(
      "robot: xarm\ntempo: 120\nsequence:\n  - move: {base: 600}\n"
      "    time: 4b\n");
  const ServoProgram& p = program_of(out);
  const compiler::PlotSong song = click_song();
  compiler::PlotOptions with;
  with.song = &song;
  const std::string plain = compiler::plot_servo_program(p, {});
  const std::string drawn = compiler::plot_servo_program(p, with);
  EXPECT_EQ(plain.find("class=\"song\""), std::string::npos);
  ASSERT_NE(drawn.find("class=\"song\""), std::string::npos);
  // One servo lane (84 + 12) from y = 74, so the song lane's frame starts at 74 + 84 + 12 = 170.
  EXPECT_NE(drawn.find("<rect x=\"150\" y=\"170\" width=\"926\" height=\"72\""), std::string::npos);
  // The grid is drawn over the song: it comes after the lane in the document.
  EXPECT_LT(drawn.find("class=\"song\""), drawn.find("class=\"grid\""));
}

}  // namespace
}  // namespace seqc::compiler
