// The audio check of a choreography's `music:` song (compiler/music/song_check.hpp), with songs
// generated in the test (tests/music/song_generator.hpp) handed to the compiler through a fake
// SongReader: every expected bar, offset and length comes from how the song was made.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "compiler/compile.hpp"
#include "compiler/show.hpp"
#include "tests/compiler/lang_test_util.hpp"
#include "tests/music/song_generator.hpp"

namespace seqc::compiler {
namespace {

using compiler::testing::MemoryFiles;
using compiler::testing::messages;

class FakeSongs final : public SongReader {
 public:
  std::map<std::string, seqc::testing::Song> songs;
  std::vector<std::string> asked;
  Result<SongSamples> read(const std::string& path) override {
    asked.push_back(path);
    auto it = songs.find(path);
    if (it == songs.end()) return make_error(path + ": No such file or directory");
    return SongSamples{it->second.samples, it->second.sample_rate};
  }
};

// 120 bpm in 4/4 (a beat 500 ms, a bar 2 s), bar 1 beat 1 at 0.75 s into the audio.
constexpr const char* kDance = R"(robot: xarm
music:
  file: music/song.wav
  downbeat: 0.750s
  tempo: 120
  meter: 4/4
sequence:
  - move: home
    time: 1s
)";

CompileOutput compile_with(const std::string& text, FakeSongs& songs) {
  MemoryFiles files;
  files.files["main.yaml"] = text;
  CompileOptions options;
  options.songs = &songs;
  return compile_file("main.yaml", files, options);
}

seqc::testing::SongSpec spec_120() {
  seqc::testing::SongSpec spec;
  spec.tempo = 120;
  spec.meter = 4;
  spec.lead_in_s = 0.75;
  spec.bars = 40;
  return spec;
}

TEST(SongCheck, ASongOnTheFilesBeatsPassesQuietly) {
  FakeSongs songs;
  songs.songs["music/song.wav"] = seqc::testing::make_song(spec_120());
  auto out = compile_with(kDance, songs);
  EXPECT_EQ(messages(out), std::vector<std::string>{});
  EXPECT_EQ(songs.asked, std::vector<std::string>{"music/song.wav"});
}

TEST(SongCheck, BeatsThatDriftFromABarAreReportedFromThatBar) {
  // Every hit from bar 33 (beat 32 x 4 = 128, counted from 0) to the end comes 41 ms late, so
  // the file's beats (on the 500 ms grid) run 41 ms ahead of the song's from bar 33.
  seqc::testing::SongSpec spec = spec_120();
  spec.late_beat = 128;
  spec.late_count = 40 * 4 - 128;
  spec.late_ms = 41;
  FakeSongs songs;
  songs.songs["music/song.wav"] = seqc::testing::make_song(spec);
  auto out = compile_with(kDance, songs);
  EXPECT_EQ(messages(out),
            std::vector<std::string>{
                "2:1 warning: the file's beats run 41 ms ahead of the song from bar 33"});
}

TEST(SongCheck, EarlyBeatsRunBehind) {
  // The file says 0.750 s but the song's bar 1 is 30 ms earlier: every file beat is 30 ms late.
  seqc::testing::SongSpec spec = spec_120();
  spec.lead_in_s = 0.72;
  FakeSongs songs;
  songs.songs["music/song.wav"] = seqc::testing::make_song(spec);
  auto out = compile_with(kDance, songs);
  EXPECT_EQ(messages(out), (std::vector<std::string>{
                               "2:1 warning: the file's beats run 30 ms behind the song from bar 1",
                               "2:1 note: paste 'downbeat: 0.720s' into the 'music:' block"}));
}

// 96 bpm in 4/4 for 12 bars (beats 0-47), bar 1 beat 1 at 0.75 s, as a file at `tempo` says it.
std::string dance_at(const std::string& tempo, const std::string& downbeat = "0.750s") {
  return "robot: xarm\nmusic:\n  file: music/song.wav\n  downbeat: " + downbeat +
         "\n  tempo: " + tempo + "\n  meter: 4/4\nsequence:\n  - move: home\n    time: 1s\n";
}

seqc::testing::SongSpec spec_96() {
  seqc::testing::SongSpec spec;
  spec.tempo = 96;
  spec.lead_in_s = 0.75;
  spec.bars = 12;
  return spec;
}

TEST(SongCheck, AWrongTempoIsSaidAsTheSongsTempoNotAsAnOffset) {
  // The file's beat k falls at k x 60/96.5 s, the song's at k x 60/96 s: the song's is later by
  // k x 3.238 ms. Bar 2 (beats 4-7) stays within 20 ms; from bar 3 (beat 8: 26 ms) it grows to
  // beat 47, the last (152 ms). Not "89 ms ahead" (their mean): the song's own tempo, and the line
  // that fixes the file.
  FakeSongs songs;
  songs.songs["music/song.wav"] = seqc::testing::make_song(spec_96());
  auto out = compile_with(dance_at("96.5"), songs);
  EXPECT_EQ(messages(out), (std::vector<std::string>{
                               "2:1 warning: the song runs at 96.0 bpm; the file says 96.5 "
                               "(from bar 3 its beats run ahead by 26 ms, growing to 152 ms)",
                               "2:1 note: paste 'tempo: 96' into the 'music:' block"}));
}

TEST(SongCheck, APureOffsetIsSaidAsTheDownbeatToPaste) {
  // The song's bar 1 is at 0.790 s, the file says 0.750 s: every beat 40 ms later, at the right
  // tempo.
  seqc::testing::SongSpec spec = spec_96();
  spec.lead_in_s = 0.79;
  FakeSongs songs;
  songs.songs["music/song.wav"] = seqc::testing::make_song(spec);
  auto out = compile_with(dance_at("96"), songs);
  EXPECT_EQ(messages(out),
            (std::vector<std::string>{
                "2:1 warning: the file's beats run 40 ms ahead of the song from bar 1",
                "2:1 note: paste 'downbeat: 0.790s' into the 'music:' block"}));
}

TEST(SongCheck, ATempoChangeTheFileMissesIsSaidAsItsChangesEntry) {
  // The song goes from 120 to 122 bpm at bar 9; the file stays at 120. From bar 9 the song's
  // beats come 500 - 491.80 = 8.2 ms sooner each beat: the file's beats run behind.
  seqc::testing::SongSpec spec = spec_120();
  spec.bars = 14;
  spec.change_bar = 9;
  spec.change_tempo = 122;
  FakeSongs songs;
  songs.songs["music/song.wav"] = seqc::testing::make_song(spec);
  auto out = compile_with(kDance, songs);
  const std::vector<std::string> m = messages(out);
  ASSERT_EQ(m.size(), 2u) << ::testing::PrintToString(m);
  EXPECT_EQ(m[0].rfind("2:1 warning: from bar 9 the song runs at 122.0 bpm; the file says 120 "
                       "(from bar 10 its beats run behind by ",
                       0),
            0u)
      << m[0];
  EXPECT_EQ(m[1], "2:1 note: paste '- {bar: 9, tempo: 122}' under 'changes:'");
}

TEST(SongCheck, AMissingSongIsAnErrorAtItsFileName) {
  FakeSongs songs;
  auto out = compile_with(kDance, songs);
  EXPECT_EQ(messages(out),
            std::vector<std::string>{
                "3:9 error: cannot use the song: music/song.wav: No such file or directory"});
  EXPECT_FALSE(out.program.has_value());
}

TEST(SongCheck, EveryMistakeOfAMusicBlockIsSaidInOneRun) {
  // A bad tempo, an unknown key, a bad downbeat and a missing file: four located errors, and the
  // steps that count beats by the bad tempo add none.
  FakeSongs songs;
  auto out = compile_with(R"(robot: xarm
music:
  file: music/song.wav
  downbeat: soon
  tempo: fast
  meter: 4/4
  volume: 3
sequence:
  - move: home
    time: 2b
  - move: {base: 600}
    time: 1bar
)",
                          songs);
  EXPECT_EQ(messages(out),
            (std::vector<std::string>{
                "7:3 error: unknown key 'volume' in 'music'",
                "4:13 error: 'downbeat' is where bar 1 beat 1 falls in the audio, in seconds or "
                "milliseconds, e.g. 'downbeat: 0.750s'",
                "5:10 error: 'tempo' must be beats per minute between 1 and 1000, e.g. "
                "'tempo: 120'",
                "3:9 error: cannot use the song: music/song.wav: No such file or directory",
            }));
  EXPECT_FALSE(out.program.has_value());
}

TEST(SongCheck, AMusicBlockWithoutTempoOrMeterNamesBothAndNothingElse) {
  // The steps counting beats and bars add no "no 'tempo' is set" of their own.
  FakeSongs songs;
  songs.songs["music/song.wav"] = seqc::testing::make_song(spec_120());
  auto out = compile_with(R"(robot: xarm
music:
  file: music/song.wav
sequence:
  - move: home
    time: 2b
  - move: {base: 600}
    time: 1bar
)",
                          songs);
  EXPECT_EQ(messages(out),
            (std::vector<std::string>{
                "2:1 error: 'music' needs the song's 'tempo' (e.g. 'tempo: 128') at bar 1",
                "2:1 error: 'music' needs the song's 'meter' (e.g. 'meter: 4/4') at bar 1",
            }));
}

TEST(SongCheck, AMissingSongIsSaidBesideTheStepsMistakes) {
  FakeSongs songs;
  auto out = compile_with(R"(robot: xarm
music:
  file: music/song.wav
  tempo: 120
  meter: 4/4
sequence:
  - move: {bse: 500}
    time: 1b
)",
                          songs);
  const std::vector<std::string> m = messages(out);
  ASSERT_EQ(m.size(), 2u) << ::testing::PrintToString(m);
  EXPECT_EQ(m[1], "3:9 error: cannot use the song: music/song.wav: No such file or directory");
}

TEST(SongCheck, ADanceLongerThanTheSongSaysByHowMuch) {
  // A 10 s click track at 120 bpm; the dance is 12 s from the downbeat at 0.75 s, so it ends
  // 12.75 s into the audio: 2.75 s past its end.
  FakeSongs songs;
  songs.songs["music/song.wav"] = seqc::testing::make_clicks(120, 4, 0.75, 10, 22050);
  auto out = compile_with(R"(robot: xarm
music:
  file: music/song.wav
  downbeat: 0.750s
  tempo: 120
  meter: 4/4
sequence:
  - move: home
    time: 6bar
)",
                          songs);
  EXPECT_EQ(messages(out), std::vector<std::string>{
                               "2:1 warning: the dance runs 2.750 s past the end of the song (it "
                               "ends 12.750 s into the audio, which lasts 10.000 s)"});
}

// A show's performers get the same song check as a choreography checked alone, each in its
// own file; performers naming different downbeats are said in the show file, with both.
TEST(SongCheck, EveryPerformerOfAShowIsCheckedAgainstItsSong) {
  seqc::testing::SongSpec spec = spec_120();
  spec.late_beat = 128;
  spec.late_count = 40 * 4 - 128;
  spec.late_ms = 41;
  FakeSongs songs;
  songs.songs["music/song.wav"] = seqc::testing::make_song(spec);
  MemoryFiles files;
  files.files["duet.yaml"] =
      "show: duet\nperformers:\n  arm: {file: arm.yaml}\n  second: {file: second.yaml}\n";
  files.files["arm.yaml"] = kDance;
  std::string second = kDance;
  second.replace(second.find("0.750s"), 6, "0.800s");
  files.files["second.yaml"] = second;
  CompileOptions options;
  options.songs = &songs;
  const ShowOutput show = load_show("duet.yaml", files, options);
  ASSERT_EQ(show.performers.size(), 2u);
  EXPECT_EQ(messages(show.performers[0].output),
            std::vector<std::string>{
                "2:1 warning: the file's beats run 41 ms ahead of the song from bar 33"});
  // 50 ms later on the same song: every beat runs 50 ms behind, then 9 ms ahead from bar 33.
  EXPECT_EQ(messages(show.performers[1].output),
            (std::vector<std::string>{
                "2:1 warning: the file's beats run 50 ms behind the song from bar 1",
                "2:1 note: paste 'downbeat: 0.750s' into the 'music:' block"}));
  CompileOutput own;
  own.diagnostics = show.diagnostics;
  EXPECT_EQ(messages(own),
            std::vector<std::string>{
                "4:3 warning: performers 'arm' and 'second' dance to different songs or "
                "downbeats (music/song.wav at 0.750 s, music/song.wav at 0.800 s); a show plays "
                "one song, so `seqc show --music` would refuse it"});
}

TEST(SongCheck, WithoutAReaderNothingIsDecoded) {
  MemoryFiles files;
  files.files["main.yaml"] = kDance;
  auto out = compile_file("main.yaml", files, CompileOptions{});
  EXPECT_EQ(messages(out), std::vector<std::string>{});
  EXPECT_TRUE(out.program.has_value());
}

}  // namespace
}  // namespace seqc::compiler
