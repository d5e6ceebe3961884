// An AudioOutput on an io::Clock the caller drives, for tests: it "plays" from the instant
// start() is called at exactly the sample rate, with the latency it was given, and records what
// was asked of it. No sound is made.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "runtime/audio/audio_output.hpp"

namespace seqc::audio {

// What a ManualAudioOutput was asked to do. It is shared with the factory that opened the
// output, so a test can read it after the command has closed (destroyed) the output.
class ManualPlayback {
 public:
  const std::optional<io::TimePoint>& started_at() const { return started_; }
  const PcmAudio& played() const { return audio_; }
  bool stopped() const { return stopped_; }

 private:
  friend class ManualAudioOutput;
  PcmAudio audio_;
  std::optional<io::TimePoint> started_;
  bool stopped_ = false;
};

class ManualAudioOutput final : public AudioOutput {
 public:
  ManualAudioOutput(io::Clock& clock, io::Duration latency)
      : clock_(clock), latency_(latency), record_(std::make_shared<ManualPlayback>()) {}

  // Makes start() fail with `message` (a sound server that refuses the stream).
  void fail_start(std::string message) { failure_ = std::move(message); }

  Status start(const PcmAudio& audio) override {
    if (failure_) return make_error(*failure_);
    record_->audio_ = audio;
    record_->started_ = clock_.now();
    return Ok{};
  }
  Result<PlaybackClock> clock() override {
    const PcmAudio& audio = record_->audio_;
    if (!record_->started_) return make_error("the audio has not started");
    const io::TimePoint now = clock_.now();
    const double seconds = std::chrono::duration<double>(now - *record_->started_).count();
    auto written = static_cast<std::int64_t>(seconds * audio.sample_rate);
    if (written > audio.frames()) written = audio.frames();
    return PlaybackClock{now, written, latency_, audio.sample_rate};
  }
  bool finished() override {
    if (record_->stopped_ || !record_->started_) return record_->stopped_;
    const PcmAudio& audio = record_->audio_;
    const auto length = std::chrono::duration_cast<io::Duration>(
        std::chrono::duration<double>(static_cast<double>(audio.frames()) / audio.sample_rate));
    return clock_.now() >= *record_->started_ + latency_ + length;
  }
  void stop() override { record_->stopped_ = true; }
  std::string describe() const override { return "a manual audio clock"; }

  // What the test reads back (also through the record, after the output is gone).
  const std::optional<io::TimePoint>& started_at() const { return record_->started_at(); }
  const PcmAudio& played() const { return record_->played(); }
  bool stopped() const { return record_->stopped(); }
  std::shared_ptr<const ManualPlayback> record() const { return record_; }

 private:
  io::Clock& clock_;
  io::Duration latency_;
  std::optional<std::string> failure_;
  std::shared_ptr<ManualPlayback> record_;
};

// Hands out ManualAudioOutputs (or an error: no sound server) and keeps what the last one was
// asked to do.
class ManualAudioOutputFactory final : public AudioOutputFactory {
 public:
  ManualAudioOutputFactory(io::Clock& clock, io::Duration latency)
      : clock_(clock), latency_(latency) {}
  void fail_open(std::string message) { failure_ = std::move(message); }
  Result<std::unique_ptr<AudioOutput>> open() override {
    if (failure_) return make_error(*failure_);
    auto out = std::make_unique<ManualAudioOutput>(clock_, latency_);
    last_ = out->record();
    return std::unique_ptr<AudioOutput>(std::move(out));
  }
  // What the output last opened was asked to do (valid after it is closed), or null.
  const ManualPlayback* last() const { return last_.get(); }

 private:
  io::Clock& clock_;
  io::Duration latency_;
  std::optional<std::string> failure_;
  std::shared_ptr<const ManualPlayback> last_;
};

}  // namespace seqc::audio
