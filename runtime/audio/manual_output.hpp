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

class ManualAudioOutput final : public AudioOutput {
 public:
  ManualAudioOutput(io::Clock& clock, io::Duration latency) : clock_(clock), latency_(latency) {}

  // Makes start() fail with `message` (a sound server that refuses the stream).
  void fail_start(std::string message) { failure_ = std::move(message); }

  Status start(const PcmAudio& audio) override {
    if (failure_) return make_error(*failure_);
    audio_ = audio;
    started_ = clock_.now();
    return Ok{};
  }
  Result<PlaybackClock> clock() override {
    if (!started_) return make_error("the audio has not started");
    const io::TimePoint now = clock_.now();
    const double seconds = std::chrono::duration<double>(now - *started_).count();
    auto written = static_cast<std::int64_t>(seconds * audio_.sample_rate);
    if (written > audio_.frames()) written = audio_.frames();
    return PlaybackClock{now, written, latency_, audio_.sample_rate};
  }
  bool finished() override {
    if (stopped_ || !started_) return stopped_;
    const auto length = std::chrono::duration_cast<io::Duration>(
        std::chrono::duration<double>(static_cast<double>(audio_.frames()) / audio_.sample_rate));
    return clock_.now() >= *started_ + latency_ + length;
  }
  void stop() override { stopped_ = true; }
  std::string describe() const override { return "a manual audio clock"; }

  // What the test reads back.
  const std::optional<io::TimePoint>& started_at() const { return started_; }
  const PcmAudio& played() const { return audio_; }
  bool stopped() const { return stopped_; }

 private:
  io::Clock& clock_;
  io::Duration latency_;
  std::optional<std::string> failure_;
  PcmAudio audio_;
  std::optional<io::TimePoint> started_;
  bool stopped_ = false;
};

// Hands out one ManualAudioOutput the test keeps (or an error: no sound server).
class ManualAudioOutputFactory final : public AudioOutputFactory {
 public:
  ManualAudioOutputFactory(io::Clock& clock, io::Duration latency)
      : clock_(clock), latency_(latency) {}
  void fail_open(std::string message) { failure_ = std::move(message); }
  Result<std::unique_ptr<AudioOutput>> open() override {
    if (failure_) return make_error(*failure_);
    auto out = std::make_unique<ManualAudioOutput>(clock_, latency_);
    last_ = out.get();
    return std::unique_ptr<AudioOutput>(std::move(out));
  }
  // The output last opened (owned by whoever opened it), or null.
  ManualAudioOutput* last() const { return last_; }

 private:
  io::Clock& clock_;
  io::Duration latency_;
  std::optional<std::string> failure_;
  ManualAudioOutput* last_ = nullptr;
};

}  // namespace seqc::audio
