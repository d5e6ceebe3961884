// The libsndfile reader and writer on files in a temporary folder: what is written reads back
// to 16-bit precision, several channels become their mean, and every failure is an Error that
// names the file; a WAV is written as every output is (runtime/io/disk.hpp).
#include <gtest/gtest.h>
#include <sndfile.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "runtime/audio/sndfile_audio.hpp"

namespace seqc::audio {
namespace {

namespace fs = std::filesystem;

class SndfileAudio : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("seqc-audio-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            "-" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

TEST_F(SndfileAudio, WavRoundTripsTo16Bits) {
  MonoAudio audio;
  audio.sample_rate = 8000;
  for (int i = 0; i < 800; ++i) audio.samples.push_back(0.5f * std::sin(0.05f * float(i)));
  audio.samples.push_back(1.5f);  // clipped to full scale, not wrapped
  SndfileAudioWriter writer;
  ASSERT_TRUE(writer.write_wav(path("a.wav"), audio).ok());
  EXPECT_FALSE(fs::exists(path("a.wav.part")));
  SndfileAudioReader reader;
  auto back = reader.read(path("a.wav"));
  ASSERT_TRUE(back.ok()) << back.error().message;
  EXPECT_EQ(back->sample_rate, 8000);
  ASSERT_EQ(back->samples.size(), audio.samples.size());
  for (std::size_t i = 0; i < 800; ++i) {
    EXPECT_NEAR(back->samples[i], audio.samples[i], 1.0 / 32768) << i;
  }
  EXPECT_NEAR(back->samples.back(), 1.0f, 1.0 / 32768);
}

TEST_F(SndfileAudio, StereoIsTheMeanOfItsChannels) {
  // Left 0.5, right -0.25: mono 0.125. Written as 16-bit FLAC with libsndfile itself.
  SF_INFO info{};
  info.samplerate = 22050;
  info.channels = 2;
  info.format = SF_FORMAT_FLAC | SF_FORMAT_PCM_16;
  SNDFILE* f = sf_open(path("s.flac").c_str(), SFM_WRITE, &info);
  ASSERT_NE(f, nullptr) << sf_strerror(nullptr);
  std::vector<float> frames;
  for (int i = 0; i < 100; ++i) frames.insert(frames.end(), {0.5f, -0.25f});
  ASSERT_EQ(sf_writef_float(f, frames.data(), 100), 100);
  sf_close(f);
  auto mono = SndfileAudioReader().read(path("s.flac"));
  ASSERT_TRUE(mono.ok()) << mono.error().message;
  EXPECT_EQ(mono->sample_rate, 22050);
  ASSERT_EQ(mono->samples.size(), 100u);
  for (float s : mono->samples) EXPECT_NEAR(s, 0.125f, 2.0 / 32768);
}

TEST_F(SndfileAudio, FailuresNameTheFile) {
  SndfileAudioReader reader;
  auto missing = reader.read(path("none.wav"));
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().message, path("none.wav") + ": no such file");
  std::ofstream(path("text.wav")) << "not audio at all\n";
  auto text = reader.read(path("text.wav"));
  ASSERT_FALSE(text.ok());
  EXPECT_EQ(text.error().message.rfind(path("text.wav") + ": cannot decode: ", 0), 0u)
      << text.error().message;
  auto folder = reader.read(dir_.string());
  ASSERT_FALSE(folder.ok());
  EXPECT_EQ(folder.error().message, dir_.string() + ": is a directory");
  MonoAudio audio{{0.0f, 0.1f}, 8000};
  const Status unwritable = SndfileAudioWriter().write_wav(path("no/such/dir/x.wav"), audio);
  ASSERT_FALSE(unwritable.ok());
  EXPECT_EQ(unwritable.error().message.rfind(path("no/such/dir/x.wav") + ": cannot write: ", 0), 0u)
      << unwritable.error().message;
}

TEST_F(SndfileAudio, WritesAsTheSafeWriterDoes) {
  // A link planted at the name a former version wrote through is neither followed nor removed.
  std::ofstream(path("precious")) << "keep me\n";
  fs::create_symlink(path("precious"), path("click.wav.part"));
  MonoAudio audio{std::vector<float>(800, 0.25f), 8000};
  ASSERT_TRUE(SndfileAudioWriter().write_wav(path("click.wav"), audio).ok());
  std::ifstream kept(path("precious"));
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(kept), {}), "keep me\n");
  EXPECT_TRUE(fs::is_symlink(path("click.wav.part")));
  auto back = SndfileAudioReader().read(path("click.wav"));
  ASSERT_TRUE(back.ok()) << back.error().message;
  EXPECT_EQ(back->samples.size(), 800u);
  // A device is written where it is and stays a device.
  ASSERT_TRUE(SndfileAudioWriter().write_wav("/dev/null", audio).ok());
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
}

TEST_F(SndfileAudio, LongSongsAreRefusedUnread) {
  MonoAudio audio{std::vector<float>(8000 * 3, 0.0f), 8000};
  ASSERT_TRUE(SndfileAudioWriter().write_wav(path("3s.wav"), audio).ok());
  auto refused = SndfileAudioReader(2.0).read(path("3s.wav"));
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().message, path("3s.wav") + ": longer than 2 s, the most seqc reads");
  EXPECT_TRUE(SndfileAudioReader(3.5).read(path("3s.wav")).ok());
}

}  // namespace
}  // namespace seqc::audio
