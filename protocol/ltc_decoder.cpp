#include "protocol/ltc_decoder.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

namespace seqc::ltc {
namespace {

// The sync word as bits 64-79 arrive when played forwards, and as they arrive backwards.
constexpr std::uint8_t kSyncForward[16] = {0, 0, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 0, 1};
constexpr std::uint8_t kSyncBackward[16] = {1, 0, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 0, 0};

constexpr double kDcSeconds = 0.1;         // the DC tracker's time constant
constexpr double kEnvelopeSeconds = 0.05;  // the peak follower's
constexpr double kHysteresis = 0.25;       // of the peak

int field(const std::uint8_t* bits, int first, int count) {
  int value = 0;
  for (int i = 0; i < count; ++i) value |= bits[first + i] << i;
  return value;
}

}  // namespace

std::int64_t LtcFrame::end_sample() const {
  return static_cast<std::int64_t>(std::ceil(end_position));
}

bool polarity_correction(const LtcFrame& frame, FrameRate rate) {
  return rate == FrameRate::Fps25 ? frame.bit59 : frame.bit27;
}

Result<LtcDecoder> LtcDecoder::create(double sample_rate) {
  if (!(sample_rate >= kMinSampleRate && sample_rate <= kMaxSampleRate)) {
    return make_error("timecode is read at 8000-96000 Hz, not " +
                      std::to_string(std::lround(sample_rate)) + " Hz");
  }
  return LtcDecoder(sample_rate);
}

LtcDecoder::LtcDecoder(double sample_rate)
    : rate_(sample_rate),
      min_cell_(sample_rate / (80 * 30 * 1.25)),
      max_cell_(sample_rate / (80 * 24 * 0.8)),
      cell_(sample_rate / (80 * 27)),
      dc_alpha_(1.0 - std::exp(-1.0 / (kDcSeconds * sample_rate))),
      envelope_decay_(std::exp(-1.0 / (kEnvelopeSeconds * sample_rate))) {}

void LtcDecoder::feed(std::span<const float> samples, std::vector<LtcFrame>& frames) {
  for (const float raw : samples) {
    const double index = static_cast<double>(fed_);
    dc_ += (raw - dc_) * dc_alpha_;
    const auto x = static_cast<float>(raw - dc_);
    envelope_ = std::max(static_cast<double>(std::fabs(x)), envelope_ * envelope_decay_);
    // Where the signal last passed zero, between this sample and the one before.
    if ((previous_ <= 0 && x > 0) || (previous_ >= 0 && x < 0)) {
      last_zero_ = index - 1 + static_cast<double>(previous_) / (previous_ - x);
    }
    previous_ = x;
    const double threshold = std::max(static_cast<double>(kFloor), kHysteresis * envelope_);
    const int level = x > threshold ? 1 : x < -threshold ? -1 : 0;
    if (level != 0 && level != level_) {
      // Out of silence, the level change is within the last sample whatever side of the
      // (tracked) DC the silence sat on.
      const double at = level_ == 0 ? std::max(last_zero_, index - 1) : last_zero_;
      level_ = level;
      crossing(at, frames);
    }
    ++fed_;
    // Silence for longer than any interval a frame holds: what comes next starts afresh.
    if (last_crossing_ && index - *last_crossing_ > 1.5 * max_cell_) forget_signal();
  }
}

void LtcDecoder::forget_signal() {
  level_ = 0;
  last_crossing_.reset();
  drop_bits();
  last_frame_.reset();
  frame_samples_ = 0;
  max_frame_number_ = -1;
  counted_per_second_ = 0;
}

void LtcDecoder::drop_bits() {
  half_pending_ = false;
  bit_count_ = 0;
}

void LtcDecoder::crossing(double position, std::vector<LtcFrame>& frames) {
  if (!last_crossing_) {
    last_crossing_ = position;
    return;
  }
  const double interval = position - *last_crossing_;
  last_crossing_ = position;
  if (interval < 0.5 * min_cell_ * 0.5 || interval > 1.5 * max_cell_) {
    drop_bits();  // a glitch far shorter than any half cell, or a gap longer than any cell
    return;
  }
  if (interval >= 0.75 * cell_) {
    if (half_pending_) drop_bits();  // a half cell alone: the pairing was wrong
    cell_ = std::clamp(cell_ + (interval - cell_) * 0.25, min_cell_, max_cell_);
    push_bit(false, position, frames);
    return;
  }
  if (!half_pending_) {
    half_pending_ = true;
    half_length_ = interval;
    return;
  }
  half_pending_ = false;
  cell_ = std::clamp(cell_ + (half_length_ + interval - cell_) * 0.25, min_cell_, max_cell_);
  push_bit(true, position, frames);
}

void LtcDecoder::push_bit(bool one, double end, std::vector<LtcFrame>& frames) {
  if (bit_count_ == kHistory) {
    std::memmove(bits_, bits_ + 1, kHistory - 1);
    std::memmove(bit_ends_, bit_ends_ + 1, (kHistory - 1) * sizeof(double));
    --bit_count_;
  }
  bits_[bit_count_] = one ? 1 : 0;
  bit_ends_[bit_count_] = end;
  ++bit_count_;
  if (bit_count_ < 80) return;
  const std::uint8_t* last16 = bits_ + bit_count_ - 16;
  if (std::memcmp(last16, kSyncForward, 16) == 0) {
    take_frame(bits_ + bit_count_ - 80, false, end, frames);
  } else if (std::memcmp(last16, kSyncBackward, 16) == 0) {
    // Played backwards: the 64 bits before this sync word are a frame's bits 63..0; the frame
    // ended where its bit 0 did.
    std::uint8_t forward[80];
    const std::uint8_t* data = bits_ + bit_count_ - 80;
    for (int k = 0; k < 64; ++k) forward[k] = data[63 - k];
    std::memcpy(forward + 64, kSyncForward, 16);
    take_frame(forward, true, bit_ends_[bit_count_ - 17], frames);
  }
}

void LtcDecoder::take_frame(const std::uint8_t* bits, bool reverse, double end,
                            std::vector<LtcFrame>& frames) {
  const int frame_units = field(bits, 0, 4), frame_tens = field(bits, 8, 2);
  const int secs_units = field(bits, 16, 4), secs_tens = field(bits, 24, 3);
  const int mins_units = field(bits, 32, 4), mins_tens = field(bits, 40, 3);
  const int hours_units = field(bits, 48, 4), hours_tens = field(bits, 56, 2);
  LtcFrame frame;
  frame.timecode = {hours_tens * 10 + hours_units, mins_tens * 10 + mins_units,
                    secs_tens * 10 + secs_units, frame_tens * 10 + frame_units, bits[10] != 0};
  const bool digits_ok = frame_units <= 9 && secs_units <= 9 && mins_units <= 9 && hours_units <= 9;
  const FrameRate widest = frame.timecode.drop_frame ? FrameRate::Fps2997Drop : FrameRate::Fps30;
  if (!digits_ok || !exists_at(frame.timecode, widest)) {
    ++rejected_;
    return;
  }
  frame.color_frame = bits[11] != 0;
  for (int group = 0; group < 8; ++group) {
    frame.user_bits |= static_cast<std::uint32_t>(field(bits, 4 + 8 * group, 4)) << (4 * group);
  }
  frame.bit27 = bits[27] != 0;
  frame.bit43 = bits[43] != 0;
  frame.bit58 = bits[58] != 0;
  frame.bit59 = bits[59] != 0;
  frame.reverse = reverse;
  frame.end_position = end;

  // What this frame says about the rate, when it follows the last one.
  if (last_frame_ && !reverse && !last_frame_->reverse) {
    const double gap = end - last_frame_->end_position;
    const double longest = 80 * max_cell_;
    if (gap > 0 && gap <= longest) {
      frame_samples_ = frame_samples_ == 0 ? gap : frame_samples_ + (gap - frame_samples_) * 0.25;
      const Timecode& before = last_frame_->timecode;
      if (frame.timecode.frames == 0 && before.seconds != frame.timecode.seconds &&
          before.frames >= 23) {
        counted_per_second_ = before.frames + 1;
      }
    }
  }
  max_frame_number_ = std::max(max_frame_number_, frame.timecode.frames);
  last_frame_ = frame;
  frames.push_back(frame);
}

std::optional<FrameRate> LtcDecoder::rate() const {
  if (!last_frame_ || frame_samples_ == 0) return std::nullopt;
  if (last_frame_->timecode.drop_frame) return FrameRate::Fps2997Drop;
  if (counted_per_second_ == 24) return FrameRate::Fps24;
  if (counted_per_second_ == 25) return FrameRate::Fps25;
  if (counted_per_second_ == 30) return FrameRate::Fps30;
  if (max_frame_number_ >= 25) return FrameRate::Fps30;
  const double fps = rate_ / frame_samples_;
  if (fps < 24.5 && max_frame_number_ < 24) return FrameRate::Fps24;
  return fps < 27.5 ? FrameRate::Fps25 : FrameRate::Fps30;
}

}  // namespace seqc::ltc
