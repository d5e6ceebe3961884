// SMPTE linear timecode (LTC) from audio samples: a biphase-mark bit decoder and the 80-bit
// frame it carries (docs/protocol/ltc.md). Pure: samples in, frames out, no I/O, no clock.
//
// Bits: every bit cell starts with a level change and a "1" has one more in its middle, so
// only the intervals between zero crossings matter (an inverted signal decodes the same). A
// crossing is where the signal, DC removed, passes zero between two samples (interpolated),
// counted once it has gone past a hysteresis threshold (a quarter of the recent peak, at least
// kFloor). The cell's length is learnt as it goes (a quarter of each new cell's difference);
// an interval of at least three quarters of a cell is a "0", two shorter ones a "1".
//
// Limits, whatever the input: bit cells are taken between sample_rate / (80 x 30 x 1.25) and
// sample_rate / (80 x 24 x 0.8) (24-30 fps within 20-25 % varispeed), so a frame never spans
// more than sample_rate / 19.2 samples (2,500 at 48 kHz); an interval longer than 1.5 of the
// longest cell (silence, a dropout) drops every bit gathered and waits for the next level
// change, and a half cell not followed by its other half drops them too. Memory is fixed (the
// last 96 bits); sample rates from 8 kHz to 96 kHz.
//
// Frames: on the sync word 0011 1111 1111 1101 as the last 16 bits (played forwards) or
// 1011 1111 1111 1100 (played backwards: the frame is the 64 bits before it, read back to
// front). A frame whose BCD digits are out of range (frames past 29, seconds past 59, hours
// past 23, a digit past 9, a drop-frame label drop-frame skips) is counted and dropped.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "base/result.hpp"
#include "protocol/ltc_timecode.hpp"

namespace seqc::ltc {

struct LtcFrame {
  Timecode timecode;            // drop_frame is bit 10
  bool color_frame = false;     // bit 11
  std::uint32_t user_bits = 0;  // the eight binary groups, group 1 (bits 4-7) the low nibble
  bool bit27 = false;           // polarity correction at 24 and 30 fps; BGF0 at 25
  bool bit43 = false;           // BGF0 at 24 and 30 fps; BGF2 at 25
  bool bit58 = false;           // BGF1
  bool bit59 = false;           // BGF2 at 24 and 30 fps; polarity correction at 25
  bool reverse = false;         // read with the sync word backwards (tape played backwards)
  // Where the frame ended: the crossing after its last bit, as a sample index (fractional:
  // interpolated between samples) counted from the first sample ever fed.
  double end_position = 0;
  std::int64_t end_sample() const;  // end_position rounded up: the first sample after it
};

// The polarity-correction bit of `frame` at `rate`: bit 59 at 25 fps, bit 27 otherwise.
bool polarity_correction(const LtcFrame& frame, FrameRate rate);

class LtcDecoder {
 public:
  static constexpr double kMinSampleRate = 8000;
  static constexpr double kMaxSampleRate = 96000;
  static constexpr float kFloor = 0.005f;  // the least hysteresis: -46 dBFS

  // An Error when `sample_rate` is outside 8 kHz-96 kHz.
  static Result<LtcDecoder> create(double sample_rate);

  // Decodes the next samples (mono, about [-1, 1]) and appends each frame they complete.
  void feed(std::span<const float> samples, std::vector<LtcFrame>& frames);

  double sample_rate() const { return rate_; }
  std::int64_t samples_fed() const { return fed_; }
  // Frames whose sync word was found but whose digits were out of range.
  std::int64_t frames_rejected() const { return rejected_; }

  // The rate the frames are counted at, once it can be told: from the frame numbers counted
  // in a second (the number before a 0 where the seconds change), else the drop-frame flag,
  // else the highest frame number seen (25-29: 30 fps; 24: not 24 fps), else the measured
  // length of a frame (nearest of 24, 25, 30 fps). Nothing before two consecutive frames.
  // Forgotten when the signal drops out.
  std::optional<FrameRate> rate() const;
  // The measured length of a frame in samples (0 before two consecutive frames).
  double samples_per_frame() const { return frame_samples_; }

 private:
  explicit LtcDecoder(double sample_rate);
  void crossing(double position, std::vector<LtcFrame>& frames);
  void push_bit(bool one, double end, std::vector<LtcFrame>& frames);
  void drop_bits();
  void forget_signal();
  void take_frame(const std::uint8_t* bits, bool reverse, double end,
                  std::vector<LtcFrame>& frames);

  static constexpr int kHistory = 96;

  double rate_;
  double min_cell_;
  double max_cell_;
  double cell_;
  std::int64_t fed_ = 0;
  std::int64_t rejected_ = 0;
  // The level detector.
  double dc_ = 0;
  double dc_alpha_;
  double envelope_ = 0;
  double envelope_decay_;
  int level_ = 0;  // +1 high, -1 low, 0 not known (silence)
  float previous_ = 0;
  double last_zero_ = 0;
  std::optional<double> last_crossing_;
  // The bit assembler.
  bool half_pending_ = false;
  double half_length_ = 0;
  std::uint8_t bits_[kHistory] = {};
  double bit_ends_[kHistory] = {};
  int bit_count_ = 0;  // valid bits in the history (up to kHistory), newest at the end
  // What the frames so far say about the rate.
  std::optional<LtcFrame> last_frame_;
  double frame_samples_ = 0;
  int max_frame_number_ = -1;
  int counted_per_second_ = 0;
};

}  // namespace seqc::ltc
