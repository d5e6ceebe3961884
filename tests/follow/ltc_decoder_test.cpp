// The LTC decoder on libltc's signals (tests/follow/ltc_signal.py) at 24, 25, 29.97 drop-frame
// and 30 fps, 48 and 44.1 kHz: every frame libltc encoded, in order, with its label, ending
// where libltc's frame ended (but the last: nothing follows it); inverted, and played
// backwards.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "protocol/ltc_decoder.hpp"
#include "tests/follow/ltc_test_signals.hpp"

namespace seqc::ltc {
namespace {

struct Signal {
  const char* name;
  Timecode first;
  int frames;
  int fps;          // frames a second in the label
  double real_fps;  // frames a second in time
  FrameRate rate;
};

const Signal kSignals[] = {
    {"24", {1, 2, 3, 0, false}, 72, 24, 24.0, FrameRate::Fps24},
    {"25", {10, 0, 0, 0, false}, 75, 25, 25.0, FrameRate::Fps25},
    {"2997df", {0, 0, 58, 0, true}, 90, 30, 30000.0 / 1001.0, FrameRate::Fps2997Drop},
    {"2997df-tenth", {0, 9, 58, 0, true}, 90, 30, 30000.0 / 1001.0, FrameRate::Fps2997Drop},
    {"30", {0, 59, 59, 0, false}, 60, 30, 30.0, FrameRate::Fps30},
};

std::vector<LtcFrame> decode(const std::vector<float>& samples, double rate, LtcDecoder* out) {
  auto decoder = LtcDecoder::create(rate);
  EXPECT_TRUE(decoder.ok());
  std::vector<LtcFrame> frames;
  // In uneven blocks, as an input hands them over.
  std::size_t at = 0;
  for (std::size_t block = 1; at < samples.size(); block = block * 3 % 1021 + 1) {
    const std::size_t n = std::min(block, samples.size() - at);
    decoder->feed(std::span<const float>(samples.data() + at, n), frames);
    at += n;
  }
  if (out != nullptr) *out = std::move(*decoder);
  return frames;
}

void expect_every_frame(const Signal& s, double sample_rate, bool inverted) {
  const std::string name =
      std::string("ltc-") + s.name + "-" + std::to_string(static_cast<int>(sample_rate));
  SCOPED_TRACE(name + (inverted ? " inverted" : ""));
  audio::MonoAudio audio = testing::read_ltc_signal(name);
  ASSERT_EQ(audio.sample_rate, sample_rate) << "missing " << testing::ltc_signal_path(name);
  if (inverted) {
    for (float& x : audio.samples) x = -x;
  }
  auto decoder = LtcDecoder::create(sample_rate);
  const std::vector<LtcFrame> frames = decode(audio.samples, sample_rate, &*decoder);
  // The last frame's end is never heard: no level change follows its last bit.
  ASSERT_EQ(static_cast<int>(frames.size()), s.frames - 1);
  Timecode expected = s.first;
  const double frame_samples = sample_rate / s.real_fps;
  for (int i = 0; i < s.frames - 1; ++i) {
    SCOPED_TRACE("frame " + std::to_string(i));
    EXPECT_EQ(frames[i].timecode, expected);
    EXPECT_FALSE(frames[i].reverse);
    EXPECT_NEAR(frames[i].end_position, (i + 1) * frame_samples, 1.5);
    expected = testing::next_label(expected, s.fps);
  }
  EXPECT_EQ(decoder->frames_rejected(), 0);
  ASSERT_TRUE(decoder->rate().has_value());
  EXPECT_EQ(*decoder->rate(), s.rate);
  EXPECT_NEAR(decoder->samples_per_frame(), frame_samples, 1.0);
}

TEST(LtcDecoder, EveryFrameAtEveryRate) {
  for (const Signal& s : kSignals) {
    for (double sample_rate : {48000.0, 44100.0}) {
      expect_every_frame(s, sample_rate, false);
      expect_every_frame(s, sample_rate, true);
    }
  }
}

TEST(LtcDecoder, DropFrameSkipsAtTheMinuteNotAtTheTenth) {
  audio::MonoAudio audio = testing::read_ltc_signal("ltc-2997df-48000");
  std::vector<LtcFrame> frames = decode(audio.samples, 48000, nullptr);
  ASSERT_EQ(frames.size(), 89u);
  // From 00:00:58;00: frame 59 is 00:00:59;29, and the next is ;02.
  EXPECT_EQ(frames[59].timecode, (Timecode{0, 0, 59, 29, true}));
  EXPECT_EQ(frames[60].timecode, (Timecode{0, 1, 0, 2, true}));
  audio = testing::read_ltc_signal("ltc-2997df-tenth-48000");
  frames = decode(audio.samples, 48000, nullptr);
  ASSERT_EQ(frames.size(), 89u);
  EXPECT_EQ(frames[59].timecode, (Timecode{0, 9, 59, 29, true}));
  EXPECT_EQ(frames[60].timecode, (Timecode{0, 10, 0, 0, true}));
}

TEST(LtcDecoder, UserBitsAndFlags) {
  const audio::MonoAudio audio = testing::read_ltc_signal("ltc-25-48000");
  const std::vector<LtcFrame> frames = decode(audio.samples, 48000, nullptr);
  ASSERT_FALSE(frames.empty());
  int ones = 0;
  for (const LtcFrame& f : frames) {
    EXPECT_EQ(f.user_bits, 0x12345678u);  // group 1 = 8 ... group 8 = 1
    EXPECT_FALSE(f.color_frame);
    EXPECT_FALSE(f.timecode.drop_frame);
    ones += polarity_correction(f, FrameRate::Fps25) ? 1 : 0;
  }
  // libltc sets the polarity-correction bit on the frames whose other bits hold an odd count of
  // zeros: some frames of a running count do, some do not.
  EXPECT_GT(ones, 0);
  EXPECT_LT(ones, static_cast<int>(frames.size()));
}

TEST(LtcDecoder, PlayedBackwards) {
  audio::MonoAudio audio = testing::read_ltc_signal("ltc-25-48000");
  std::reverse(audio.samples.begin(), audio.samples.end());
  const std::vector<LtcFrame> frames = decode(audio.samples, 48000, nullptr);
  // The last frame played first: 10:00:02:24 down to 10:00:00:00 (the first frame's sync word
  // is the last thing heard, with no frame after it to end).
  ASSERT_GE(frames.size(), 74u);
  Timecode expected{10, 0, 2, 24, false};
  for (std::size_t i = 0; i < 74; ++i) {
    SCOPED_TRACE("frame " + std::to_string(i));
    EXPECT_TRUE(frames[i].reverse);
    EXPECT_EQ(frames[i].timecode, expected);
    if (expected.frames == 0) {
      expected.frames = 24;
      --expected.seconds;
    } else {
      --expected.frames;
    }
  }
}

TEST(LtcDecoder, SilenceAndNoiseGiveNoFrame) {
  auto decoder = LtcDecoder::create(48000);
  std::vector<LtcFrame> frames;
  std::vector<float> silence(48000, 0.0f);
  decoder->feed(silence, frames);
  std::vector<float> tone(48000);
  for (std::size_t i = 0; i < tone.size(); ++i) {
    tone[i] = static_cast<float>(0.5 * std::sin(2 * M_PI * 1000 * static_cast<double>(i) / 48000));
  }
  decoder->feed(tone, frames);
  EXPECT_TRUE(frames.empty());
  EXPECT_FALSE(decoder->rate().has_value());
  EXPECT_EQ(decoder->samples_fed(), 96000);
}

TEST(LtcDecoder, RefusesSampleRatesItCannotRead) {
  EXPECT_EQ(LtcDecoder::create(7999).error().message,
            "timecode is read at 8000-96000 Hz, not 7999 Hz");
  EXPECT_EQ(LtcDecoder::create(192000).error().message,
            "timecode is read at 8000-96000 Hz, not 192000 Hz");
  EXPECT_TRUE(LtcDecoder::create(8000).ok());
  EXPECT_TRUE(LtcDecoder::create(96000).ok());
}

}  // namespace
}  // namespace seqc::ltc
