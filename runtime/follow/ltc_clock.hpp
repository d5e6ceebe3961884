// A ShowClock that chases SMPTE linear timecode heard on an audio input (`seqc follow --ltc`):
// the dance's time 0 is the `--start` timecode.
//
// Every frame is dated when it ended (its last bit), on the host's clock through the input's
// block dates; the timecode's position then is the frame's label plus one frame, so
// dance_ms = (label + 1 frame) - start, in real milliseconds at the rate the frames are counted
// at (24, 25, 29.97 drop-frame or 30 fps, as the decoder tells it).
//
//   lock        kLockFrames (4) consecutive frames forwards, each the label after the one
//               before and a frame's length after it: Open once (the first lock; its dance_ms
//               is where the timecode then is, negative before `--start`);
//   Start       on the first frame whose end is at or past `--start` (dance_ms 0 when the
//               signal runs through it, more when it locks past it); before that, it waits;
//   Sync        every `sync_every` frames while running;
//   freewheel   frames missing (a dropout), garbled or standing still: no event, the show runs
//               on; frames coming back where the running time says continue the Syncs;
//   jump        frames at another position: after kLockFrames of them in a row, a Sync at the
//               new position ("jumped to ..."), or a Stop when it is before `--start` (then a
//               Start again when it gets there);
//   Stop        no frame where the running time says for `freewheel` (2 s), timecode standing
//               still included; dated when the freewheel ran out. A later lock starts again
//               (Start, not Open).
// Frames read backwards never lock. The input ending (a WAV file) ends the clock: a Stop when
// it was running.
#pragma once

#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "protocol/ltc_decoder.hpp"
#include "protocol/ltc_timecode.hpp"
#include "runtime/audio/audio_input.hpp"
#include "runtime/follow/show_clock.hpp"

namespace seqc::follow {

struct LtcClockOptions {
  ltc::Timecode start;
  int lock_frames = 4;
  double freewheel_seconds = 2.0;
  int sync_every = 1;
  double block_seconds = 0.010;  // how much audio is read at a time
};

class LtcClock final : public ShowClock {
 public:
  // An Error when the input's sample rate is one the decoder cannot read.
  static Result<std::unique_ptr<LtcClock>> create(std::unique_ptr<audio::AudioInput> input,
                                                  io::Clock& clock, LtcClockOptions options);

  std::optional<ShowClockEvent> next(io::TimePoint deadline) override;
  bool ended() const override { return ended_ && pending_.empty(); }

  // The rate the clock locked at, once it has.
  std::optional<ltc::FrameRate> rate() const { return rate_; }
  const audio::AudioInput& input() const { return *input_; }

 private:
  LtcClock(std::unique_ptr<audio::AudioInput> input, io::Clock& clock, LtcClockOptions options,
           ltc::LtcDecoder decoder);

  void take(const ltc::LtcFrame& frame);
  void lock(const ltc::LtcFrame& frame, ltc::FrameRate rate, double frame_samples);
  void advance(const ltc::LtcFrame& frame, std::int64_t count);
  void expire(double position);
  io::TimePoint host_time(double position) const;
  double dance_ms(std::int64_t count) const;
  void push(ShowClockKind kind, double ms, double position, std::string detail);

  std::unique_ptr<audio::AudioInput> input_;
  io::Clock& clock_;
  LtcClockOptions options_;
  ltc::LtcDecoder decoder_;
  std::vector<float> block_;
  std::vector<ltc::LtcFrame> frames_;
  std::deque<ShowClockEvent> pending_;
  bool ended_ = false;
  // The samples read so far and when the last block ended, for dating positions.
  std::int64_t read_ = 0;
  io::TimePoint read_end_at_{0};
  // The lock: the rate, the last frame where the running time said (its count and where it
  // ended), a frame's length in samples, `--start` as a count at that rate.
  std::optional<ltc::FrameRate> rate_;
  std::int64_t good_count_ = 0;
  double good_end_ = 0;
  double frame_samples_ = 0;
  std::int64_t start_count_ = 0;
  bool still_ = false;  // the last frame repeated the last good one's label
  // The last frames off the running time: lock_frames consecutive ones lock.
  std::deque<ltc::LtcFrame> run_;
  bool opened_ = false;
  bool started_ = false;
  int since_sync_ = 0;
};

}  // namespace seqc::follow
