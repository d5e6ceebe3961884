// The libsndfile reader and writer on files in a temporary folder: what is written reads back
// to 16-bit precision, several channels become their mean, and every failure is an Error that
// names the file; a WAV is written as every output is (runtime/io/disk.hpp).
#include <gtest/gtest.h>
#include <sndfile.h>

#include <sys/stat.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
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

// Writes `frames` frames of `channels` channels at `rate` with libsndfile itself; value(i, c)
// is frame i's sample on channel c.
template <typename Value>
void write_song(const std::string& file, int format, int rate, int channels, int frames,
                Value value) {
  SF_INFO info{};
  info.samplerate = rate;
  info.channels = channels;
  info.format = format;
  SNDFILE* f = sf_open(file.c_str(), SFM_WRITE, &info);
  ASSERT_NE(f, nullptr) << sf_strerror(nullptr);
  std::vector<float> samples;
  for (int i = 0; i < frames; ++i) {
    for (int c = 0; c < channels; ++c) samples.push_back(value(i, c));
  }
  ASSERT_EQ(sf_writef_float(f, samples.data(), frames), frames);
  sf_close(f);
}

std::string bytes_of(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

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

TEST_F(SndfileAudio, EightChannelsAt192kHzAreMixedThenDecimatedTo48kHz) {
  // Frame i, channel c: ((i / 4) % 8 - 4 + c) / 64, exact in 16 bits. The mean of the channels is
  // ((i / 4) % 8 - 0.5) / 64, the same for the 4 frames of each group of 4 (192 / 48); the 3
  // frames of the last, partial group are dropped.
  write_song(path("8ch.flac"), SF_FORMAT_FLAC | SF_FORMAT_PCM_16, 192000, 8, 4003,
             [](int i, int c) { return float((i / 4) % 8 - 4 + c) / 64.0f; });
  auto mono = SndfileAudioReader().read(path("8ch.flac"));
  ASSERT_TRUE(mono.ok()) << mono.error().message;
  EXPECT_EQ(mono->sample_rate, 48000);
  ASSERT_EQ(mono->samples.size(), 1000u);
  for (std::size_t g = 0; g < 1000; ++g) {
    EXPECT_EQ(mono->samples[g], float(double(g % 8) - 0.5) / 64.0f) << g;
  }
}

TEST_F(SndfileAudio, A655kHzFlacIsDecimatedBy14) {
  // 655350 Hz, the most FLAC holds: 14 frames per kept sample, 46810.7 Hz.
  write_song(path("fast.flac"), SF_FORMAT_FLAC | SF_FORMAT_PCM_16, 655350, 1, 14 * 300 + 5,
             [](int i, int) { return float((i / 14) % 16) / 64.0f; });
  auto mono = SndfileAudioReader().read(path("fast.flac"));
  ASSERT_TRUE(mono.ok()) << mono.error().message;
  EXPECT_EQ(mono->sample_rate, 655350.0 / 14);
  ASSERT_EQ(mono->samples.size(), 300u);
  for (std::size_t g = 0; g < 300; ++g) EXPECT_EQ(mono->samples[g], float(g % 16) / 64.0f) << g;
}

TEST_F(SndfileAudio, SamplesPastTheLimitsAreRefused) {
  // 500 stereo frames are 1000 samples: exactly the limit; 501 are one frame too many.
  write_song(path("500.wav"), SF_FORMAT_WAV | SF_FORMAT_PCM_16, 8000, 2, 500,
             [](int, int) { return 0.25f; });
  write_song(path("501.wav"), SF_FORMAT_WAV | SF_FORMAT_PCM_16, 8000, 2, 501,
             [](int, int) { return 0.25f; });
  AudioReadLimits limits;
  limits.max_file_samples = 1000;
  EXPECT_TRUE(SndfileAudioReader(limits).read(path("500.wav")).ok());
  auto refused = SndfileAudioReader(limits).read(path("501.wav"));
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().message,
            path("501.wav") + ": more than 1000 samples (frames x channels), the most seqc reads");
  // The mono samples are counted as they are decoded.
  AudioReadLimits mono;
  mono.max_mono_samples = 500;
  EXPECT_TRUE(SndfileAudioReader(mono).read(path("500.wav")).ok());
  auto kept = SndfileAudioReader(mono).read(path("501.wav"));
  ASSERT_FALSE(kept.ok());
  EXPECT_EQ(
      kept.error().message,
      path("501.wav") + ": more than 500 samples once mixed down to mono, the most seqc keeps");
}

TEST_F(SndfileAudio, AFifoIsReadWithinItsByteLimit) {
  write_song(path("song.wav"), SF_FORMAT_WAV | SF_FORMAT_PCM_16, 8000, 1, 4000,
             [](int i, int) { return float(i % 32) / 64.0f; });
  const std::string wav = bytes_of(path("song.wav"));  // 8044 bytes: fits a pipe's buffer
  ASSERT_EQ(::mkfifo(path("fifo").c_str(), 0600), 0);
  auto feed = [&] {
    // Opening blocks until the reader has opened; the bytes then fit the pipe in one write.
    if (std::FILE* f = std::fopen(path("fifo").c_str(), "wb")) {
      std::fwrite(wav.data(), 1, wav.size(), f);
      std::fclose(f);
    }
  };
  std::thread writer(feed);
  auto mono = SndfileAudioReader().read(path("fifo"));
  writer.join();
  ASSERT_TRUE(mono.ok()) << mono.error().message;
  ASSERT_EQ(mono->samples.size(), 4000u);
  for (std::size_t i = 0; i < 4000; ++i) EXPECT_EQ(mono->samples[i], float(i % 32) / 64.0f) << i;

  AudioReadLimits small;
  small.max_stream_bytes = 8000;
  std::thread again(feed);
  auto refused = SndfileAudioReader(small).read(path("fifo"));
  again.join();
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().message,
            path("fifo") + ": more than 8000 bytes, the most seqc reads from a FIFO or device");
}

TEST_F(SndfileAudio, AFifoWithNoWriterAndDevZeroEnd) {
  ASSERT_EQ(::mkfifo(path("fifo").c_str(), 0600), 0);
  AudioReadLimits limits;
  limits.idle_seconds = 0.05;
  auto waited = SndfileAudioReader(limits).read(path("fifo"));
  ASSERT_FALSE(waited.ok());
  EXPECT_EQ(waited.error().message,
            path("fifo") + ": nothing to read for 0.05 s (a FIFO with no writer?)");
  // Not audio: refused after its first block, not read to the byte limit.
  auto zeros = SndfileAudioReader().read("/dev/zero");
  ASSERT_FALSE(zeros.ok());
  EXPECT_EQ(zeros.error().message.rfind("/dev/zero: cannot decode: ", 0), 0u)
      << zeros.error().message;
}

}  // namespace
}  // namespace seqc::audio
