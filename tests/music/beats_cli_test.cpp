// `seqc beats` through the real binary on files libsndfile writes in a temporary folder (WAV,
// FLAC, Ogg Vorbis), each a generated song whose tempo, meter and downbeat the test sets.
#include <gtest/gtest.h>
#include <sndfile.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <regex>
#include <string>

#include "tests/cli/seqc_run.hpp"
#include "tests/music/song_generator.hpp"

namespace seqc::testing {
namespace {

class BeatsCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(SEQC_BINARY_DIR) / "tests/music/tmp" /
           ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Written a block at a time (libsndfile 1.2.0's Vorbis encoder fails on one huge write).
  void write(const std::string& name, const Song& song, int format) {
    SF_INFO info{};
    info.samplerate = static_cast<int>(song.sample_rate);
    info.channels = 1;
    info.format = format;
    SNDFILE* f = sf_open((dir_ / name).c_str(), SFM_WRITE, &info);
    ASSERT_NE(f, nullptr) << sf_strerror(nullptr);
    for (std::size_t at = 0; at < song.samples.size(); at += 4096) {
      const auto n = static_cast<sf_count_t>(std::min<std::size_t>(4096, song.samples.size() - at));
      ASSERT_EQ(sf_writef_float(f, song.samples.data() + at, n), n);
    }
    sf_close(f);
  }

  fs::path dir_;
};

// The number after "key: " in the block, e.g. "tempo: 127.96" -> 127.96.
double field(const std::string& block, const std::string& key) {
  std::smatch m;
  const std::regex re("(?:^|\\n)  " + key + ": ([0-9.]+)");
  if (!std::regex_search(block, m, re)) return NAN;
  return std::stod(m[1]);
}

TEST_F(BeatsCli, WavFlacAndOggGiveTheSongsTempoMap) {
  SongSpec spec;
  spec.tempo = 124;
  spec.lead_in_s = 0.6;
  spec.bars = 20;
  spec.jitter_ms = 2;
  spec.sample_rate = 44100;
  const Song song = make_song(spec);
  write("song.wav", song, SF_FORMAT_WAV | SF_FORMAT_PCM_16);
  write("song.flac", song, SF_FORMAT_FLAC | SF_FORMAT_PCM_16);
  write("song.ogg", song, SF_FORMAT_OGG | SF_FORMAT_VORBIS);
  for (const char* name : {"song.wav", "song.flac", "song.ogg"}) {
    SCOPED_TRACE(name);
    SeqcRun r = seqc(dir_, std::string("beats ") + name);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out.rfind(std::string("music:\n  file: ") + name + "\n  downbeat: ", 0), 0u)
        << r.out;
    // 0.05 BPM and 5 ms, the targets docs/music.md gives.
    EXPECT_NEAR(field(r.out, "tempo"), 124, 0.05) << r.out;
    EXPECT_NEAR(field(r.out, "downbeat"), 0.6, 0.005) << r.out;
    EXPECT_NE(r.out.find("\n  meter: 4/4\n"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("changes"), std::string::npos) << r.out;
    EXPECT_NE(r.err.find("confidence "), std::string::npos) << r.err;
  }
}

TEST_F(BeatsCli, TempoChangeAndClickTrack) {
  SongSpec spec;
  spec.tempo = 100;
  spec.bars = 24;
  spec.change_bar = 13;
  spec.change_tempo = 90;
  spec.lead_in_s = 1.0;
  const Song song = make_song(spec);
  write("change.wav", song, SF_FORMAT_WAV | SF_FORMAT_PCM_16);
  SeqcRun r = seqc(dir_, "beats change.wav --meter 4/4 --click clicked.wav");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("\n  changes:\n    - {bar: 13, tempo: 90}\n"), std::string::npos) << r.out;
  ASSERT_TRUE(fs::exists(dir_ / "clicked.wav"));
  SF_INFO info{};
  SNDFILE* f = sf_open((dir_ / "clicked.wav").c_str(), SFM_READ, &info);
  ASSERT_NE(f, nullptr);
  EXPECT_EQ(info.frames, static_cast<sf_count_t>(song.samples.size()));
  EXPECT_EQ(info.samplerate, 22050);
  EXPECT_EQ(info.format, SF_FORMAT_WAV | SF_FORMAT_PCM_16);
  sf_close(f);
}

TEST_F(BeatsCli, ExitStatuses) {
  write("noise.wav", make_noise(10, 0.1, 22050, 5), SF_FORMAT_WAV | SF_FORMAT_PCM_16);
  SeqcRun noise = seqc(dir_, "beats noise.wav");
  EXPECT_EQ(noise.status, 1);
  EXPECT_EQ(noise.out, "");
  EXPECT_EQ(noise.err.rfind("seqc: error: noise.wav: no steady beat found (", 0), 0u) << noise.err;
  SeqcRun missing = seqc(dir_, "beats missing.wav");
  EXPECT_EQ(missing.status, 5);
  EXPECT_EQ(missing.err, "seqc: error: missing.wav: no such file\n");
  SeqcRun meter = seqc(dir_, "beats noise.wav --meter 4");
  EXPECT_EQ(meter.status, 2);
  EXPECT_EQ(meter.err,
            "seqc: error: --meter 4: give beats per bar and a beat unit, e.g. 4/4, 3/4 or 6/8\n");
  SeqcRun hint = seqc(dir_, "beats noise.wav --tempo-hint 5");
  EXPECT_EQ(hint.status, 2);
}

}  // namespace
}  // namespace seqc::testing
