// The song cache: a song is decoded once while its file is unchanged, again when it changes,
// and every time when it is no file that can be watched.
#include <gtest/gtest.h>

#include <fstream>

#include "runtime/lsp/song_cache.hpp"

namespace seqc::lsp {
namespace {

class CountingSongs final : public SongReader {
 public:
  Result<SongSamples> read(const std::string& path) override {
    ++reads;
    if (path.ends_with("missing.wav")) return make_error(path + ": No such file");
    return SongSamples{{0.5f, -0.5f}, 8000};
  }
  int reads = 0;
};

TEST(LspSongCache, DecodesOnceWhileTheFileIsUnchanged) {
  const std::string path = ::testing::TempDir() + "/seqc-lsp-song.wav";
  std::ofstream(path) << "one";
  CountingSongs songs;
  SongCache cache(songs);
  ASSERT_TRUE(cache.read(path));
  ASSERT_TRUE(cache.read(path));
  EXPECT_EQ(songs.reads, 1);
  EXPECT_EQ((*cache.read(path)).samples, (std::vector<float>{0.5f, -0.5f}));
  std::ofstream(path) << "longer";  // another size: decoded again
  ASSERT_TRUE(cache.read(path));
  EXPECT_EQ(songs.reads, 2);
  EXPECT_FALSE(cache.read("/nonexistent/missing.wav"));
  EXPECT_FALSE(cache.read("/nonexistent/missing.wav"));
  EXPECT_EQ(songs.reads, 4);
  std::remove(path.c_str());
}

}  // namespace
}  // namespace seqc::lsp
