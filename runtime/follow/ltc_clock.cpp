#include "runtime/follow/ltc_clock.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <utility>

namespace seqc::follow {
namespace {

// Whether b is the frame after a at `rate`, in label and in time (a frame's length apart,
// within a quarter of one).
bool follows(const ltc::LtcFrame& a, const ltc::LtcFrame& b, ltc::FrameRate rate,
             double frame_samples) {
  if (!ltc::exists_at(a.timecode, rate) || !ltc::exists_at(b.timecode, rate)) return false;
  if (ltc::frame_count(b.timecode, rate) != ltc::frame_count(a.timecode, rate) + 1) return false;
  return std::fabs(b.end_position - a.end_position - frame_samples) < frame_samples / 4;
}

}  // namespace

Result<std::unique_ptr<LtcClock>> LtcClock::create(std::unique_ptr<audio::AudioInput> input,
                                                   io::Clock& clock, LtcClockOptions options) {
  auto decoder = ltc::LtcDecoder::create(input->sample_rate());
  if (!decoder) return make_error(input->describe() + ": " + decoder.error().message);
  options.lock_frames = std::clamp(options.lock_frames, 2, 30);
  options.sync_every = std::max(options.sync_every, 1);
  options.block_seconds = std::clamp(options.block_seconds, 0.001, 0.1);
  return std::unique_ptr<LtcClock>(
      new LtcClock(std::move(input), clock, options, std::move(*decoder)));
}

LtcClock::LtcClock(std::unique_ptr<audio::AudioInput> input, io::Clock& clock,
                   LtcClockOptions options, ltc::LtcDecoder decoder)
    : input_(std::move(input)), clock_(clock), options_(options), decoder_(std::move(decoder)) {
  const auto block =
      std::max<long>(1, std::lround(options_.block_seconds * decoder_.sample_rate()));
  block_.resize(static_cast<std::size_t>(block));
}

std::optional<ShowClockEvent> LtcClock::next(io::TimePoint deadline) {
  for (;;) {
    if (!pending_.empty()) {
      ShowClockEvent event = std::move(pending_.front());
      pending_.pop_front();
      return event;
    }
    if (ended_ || clock_.now() >= deadline) return std::nullopt;
    auto block = input_->read(block_);
    if (!block) {
      ended_ = true;
      if (started_)
        push(ShowClockKind::Stop, dance_ms(good_count_), static_cast<double>(read_),
             block.error().message);
      continue;
    }
    read_ += static_cast<std::int64_t>(block->samples);
    read_end_at_ = block->end_at;
    frames_.clear();
    decoder_.feed(std::span<const float>(block_.data(), block->samples), frames_);
    for (const ltc::LtcFrame& frame : frames_) {
      expire(frame.end_position);
      take(frame);
    }
    expire(static_cast<double>(read_));
    if (block->samples < block_.size()) {
      ended_ = true;
      if (started_) {
        push(ShowClockKind::Stop, dance_ms(good_count_), static_cast<double>(read_),
             "the timecode input ended (" + input_->describe() + ")");
        started_ = false;
      }
    }
  }
}

void LtcClock::take(const ltc::LtcFrame& frame) {
  if (frame.reverse) {
    run_.clear();
    return;
  }
  // Where the running time says: the show goes on.
  if (rate_ && ltc::exists_at(frame.timecode, *rate_)) {
    const std::int64_t count = ltc::frame_count(frame.timecode, *rate_);
    const auto frames_on = std::llround((frame.end_position - good_end_) / frame_samples_);
    still_ = count == good_count_;
    if (frames_on > 0 && count == good_count_ + frames_on) {
      run_.clear();
      advance(frame, count);
      return;
    }
  }
  // Somewhere else, or not locked yet: a run of consecutive frames locks.
  run_.push_back(frame);
  if (static_cast<int>(run_.size()) > options_.lock_frames) run_.pop_front();
  const std::optional<ltc::FrameRate> rate = decoder_.rate();
  if (static_cast<int>(run_.size()) < options_.lock_frames || !rate) return;
  const double frame_samples = decoder_.samples_per_frame();
  for (std::size_t i = 1; i < run_.size(); ++i) {
    if (!follows(run_[i - 1], run_[i], *rate, frame_samples)) return;
  }
  run_.clear();
  lock(frame, *rate, frame_samples);
}

void LtcClock::lock(const ltc::LtcFrame& frame, ltc::FrameRate rate, double frame_samples) {
  const bool jumped = rate_.has_value();
  rate_ = rate;
  frame_samples_ = frame_samples;
  if (!ltc::exists_at(options_.start, rate)) {
    push(ShowClockKind::Stop, 0, frame.end_position,
         "--start " + ltc::to_text(options_.start) + " names no frame at " + ltc::rate_name(rate));
    ended_ = true;
    started_ = false;
    return;
  }
  start_count_ = ltc::frame_count(options_.start, rate);
  good_count_ = ltc::frame_count(frame.timecode, rate);
  good_end_ = frame.end_position;
  still_ = false;
  const double ms = dance_ms(good_count_);
  const std::string label = ltc::to_text(frame.timecode);
  if (!opened_) {
    opened_ = true;
    push(ShowClockKind::Open, ms, frame.end_position,
         "locked at " + ltc::rate_name(rate) + " on " + label);
  }
  if (started_) {
    if (ms < 0) {
      started_ = false;
      push(ShowClockKind::Stop, ms, frame.end_position,
           "the timecode went back to " + label + ", before --start " +
               ltc::to_text(options_.start));
    } else {
      since_sync_ = 0;
      push(ShowClockKind::Sync, ms, frame.end_position, "the timecode jumped to " + label);
    }
    return;
  }
  if (ms >= 0) {
    started_ = true;
    since_sync_ = 0;
    push(ShowClockKind::Start, ms, frame.end_position,
         (jumped ? "timecode " : "locked at " + ltc::rate_name(rate) + ", timecode ") + label);
  }
}

void LtcClock::advance(const ltc::LtcFrame& frame, std::int64_t count) {
  good_count_ = count;
  good_end_ = frame.end_position;
  // The decoder forgets a frame's length over a dropout: keep the locked one until it knows.
  if (decoder_.samples_per_frame() > 0) {
    frame_samples_ += (decoder_.samples_per_frame() - frame_samples_) * 0.25;
  }
  const double ms = dance_ms(count);
  if (!started_) {
    if (ms >= 0) {
      started_ = true;
      since_sync_ = 0;
      push(ShowClockKind::Start, ms, frame.end_position,
           "timecode " + ltc::to_text(frame.timecode));
    }
    return;
  }
  if (++since_sync_ >= options_.sync_every) {
    since_sync_ = 0;
    push(ShowClockKind::Sync, ms, frame.end_position, "timecode " + ltc::to_text(frame.timecode));
  }
}

void LtcClock::expire(double position) {
  if (!rate_) return;
  const double freewheel = options_.freewheel_seconds * decoder_.sample_rate();
  if (position - good_end_ <= freewheel) return;
  if (started_) {
    const std::string label = ltc::to_text(ltc::to_timecode(good_count_, *rate_));
    push(ShowClockKind::Stop, dance_ms(good_count_) + options_.freewheel_seconds * 1000,
         good_end_ + freewheel,
         still_ ? "the timecode stands still at " + label
                : "no timecode since " + label + " (freewheeled " +
                      std::to_string(std::lround(options_.freewheel_seconds * 1000)) + " ms)");
  }
  started_ = false;
  rate_.reset();
  still_ = false;
}

double LtcClock::dance_ms(std::int64_t count) const {
  // The frame's label is where it started; it ended a frame later.
  return ltc::frame_start_ms(count + 1 - start_count_, rate_.value_or(ltc::FrameRate::Fps30));
}

io::TimePoint LtcClock::host_time(double position) const {
  const double before_end = (static_cast<double>(read_) - position) / decoder_.sample_rate();
  return read_end_at_ - io::Duration{std::llround(before_end * 1e9)};
}

void LtcClock::push(ShowClockKind kind, double ms, double position, std::string detail) {
  pending_.push_back(ShowClockEvent{kind, ms, host_time(position), std::move(detail)});
}

}  // namespace seqc::follow
