// `seqc check SHOW.yaml` in-process with songs generated in the test: each performer's file gets
// the song check a choreography checked alone gets, located in that performer's file.
#include <gtest/gtest.h>

#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "runtime/cli/app.hpp"
#include "runtime/io/clock.hpp"
#include "tests/music/song_generator.hpp"

namespace seqc::cli {
namespace {

class Texts final : public seqc::FileReader {
 public:
  std::map<std::string, std::string> texts;
  Result<std::string> read(const std::string& path) override {
    auto it = texts.find(path);
    if (it == texts.end()) return make_error(path + ": No such file or directory");
    return it->second;
  }
};

class OneSong final : public seqc::SongReader {
 public:
  testing::Song song;
  Result<seqc::SongSamples> read(const std::string&) override {
    return seqc::SongSamples{song.samples, song.sample_rate};
  }
};

TEST(CheckShowSong, EveryPerformerIsCheckedAgainstItsSongInItsOwnFile) {
  // 120 bpm from 0.75 s for 40 bars; the arm says 0.750 s (on the song), a second
  // arm says 0.800 s: its beats run 50 ms behind from bar 1, and the show names both downbeats.
  testing::SongSpec spec;
  spec.tempo = 120;
  spec.lead_in_s = 0.75;
  spec.bars = 40;
  OneSong songs;
  songs.song = testing::make_song(spec);
  Texts files;
  files.texts["duet.yaml"] =
      "show: duet\nperformers:\n  arm: {file: arm.yaml}\n  second: {file: second.yaml}\n";
  const std::string dance =
      "robot: xarm\nmusic:\n  file: song.wav\n  downbeat: 0.750s\n  tempo: 120\n  meter: 4/4\n"
      "sequence:\n  - move: home\n    time: 1s\n";
  files.texts["arm.yaml"] = dance;
  std::string second = dance;
  second.replace(second.find("0.750s"), 6, "0.800s");
  files.texts["second.yaml"] = second;
  std::ostringstream out, err;
  io::ManualClock clock;
  Context ctx{out, err, clock, files};
  ctx.songs = &songs;
  const char* argv[] = {"seqc", "check", "duet.yaml"};
  EXPECT_EQ(run(3, argv, ctx), 0) << err.str();
  EXPECT_EQ(out.str(),
            "duet.yaml: show with 2 performers, 1 warning\n"
            "arm.yaml (arm): 1/1020 actions, 1.000 s, fit within 0 units\n"
            "second.yaml (second): 1/1020 actions, 1.000 s, fit within 0 units, 1 warning\n");
  EXPECT_NE(err.str().find("duet.yaml:4:3: warning: performers 'arm' and 'second' dance to "
                           "different songs or downbeats (song.wav at 0.750 s, song.wav at "
                           "0.800 s)"),
            std::string::npos)
      << err.str();
  EXPECT_NE(err.str().find("second.yaml:2:1: warning: the file's beats run 50 ms behind the song "
                           "from bar 1\n"),
            std::string::npos)
      << err.str();
  EXPECT_NE(err.str().find("second.yaml:2:1: note: paste 'downbeat: 0.750s' into the 'music:' "
                           "block\n"),
            std::string::npos)
      << err.str();
}

}  // namespace
}  // namespace seqc::cli
