// `seqc preview` through the real binary on a song longer than the file reader's 16 MiB limit:
// a generated 120 s song written by libsndfile as stereo 32-bit float WAV (21.2 MB), so the page
// must carry it re-encoded (Ogg Vorbis) rather than drop it.
#include <gtest/gtest.h>
#include <sndfile.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/cli/seqc_run.hpp"
#include "tests/music/song_generator.hpp"

namespace seqc::testing {
namespace {

TEST(PreviewSongCli, ASongOverTheReadLimitIsEmbeddedAsOggVorbis) {
  const fs::path dir = fs::path(SEQC_BINARY_DIR) / "tests/music/tmp/PreviewLongSong";
  fs::remove_all(dir);
  fs::create_directories(dir);
  SongSpec spec;
  spec.tempo = 120;
  spec.bars = 60;  // 0.75 s + 60 x 2 s: 120.75 s
  const Song song = make_song(spec);
  ASSERT_GT(song.duration_s(), 120.0);
  SF_INFO info{};
  info.samplerate = static_cast<int>(song.sample_rate);
  info.channels = 2;
  info.format = SF_FORMAT_WAV | SF_FORMAT_FLOAT;
  SNDFILE* f = sf_open((dir / "long.wav").c_str(), SFM_WRITE, &info);
  ASSERT_NE(f, nullptr) << sf_strerror(nullptr);
  std::vector<float> both(2 * 4096);
  for (std::size_t at = 0; at < song.samples.size(); at += 4096) {
    const std::size_t n = std::min<std::size_t>(4096, song.samples.size() - at);
    for (std::size_t i = 0; i < n; ++i) both[2 * i] = both[2 * i + 1] = song.samples[at + i];
    ASSERT_EQ(sf_writef_float(f, both.data(), static_cast<sf_count_t>(n)),
              static_cast<sf_count_t>(n));
  }
  sf_close(f);
  ASSERT_GT(fs::file_size(dir / "long.wav"), std::uintmax_t{16} << 20);
  std::ofstream(dir / "dance.yaml")
      << "robot: xarm\nmusic:\n  file: long.wav\n  downbeat: 0.750s\n  tempo: 120\n"
         "  meter: 4/4\nsequence:\n  - move: home\n    time: 1bar\n"
         "  - move: {base: 600}\n    time: 50bar\n";

  const SeqcRun r = seqc(dir, "preview dance.yaml -o dance.html");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
  const std::string page = slurp(dir / "dance.html");
  EXPECT_NE(page.find("<audio id=\"song\" preload=\"auto\" src=\"data:audio/ogg;base64,T2dnUw"),
            std::string::npos);  // "OggS", the stream's first page
  EXPECT_EQ(page.find("song-missing"), std::string::npos);
  EXPECT_LT(page.size(), std::size_t{4} << 20);  // 2 min of mono Vorbis at quality 0.3
  fs::remove_all(dir);
}

}  // namespace
}  // namespace seqc::testing
