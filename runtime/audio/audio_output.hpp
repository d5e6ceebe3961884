// The audio-output boundary: playing a song's samples on the host's sound server, and saying
// when each sample is heard on the host's monotonic clock (io::Clock's epoch), so a robot can
// be started on a beat as heard. seqc never guesses a latency: every figure comes from the
// audio API. Commands get an AudioOutputFactory passed in (the PulseAudio one in main, a
// ManualAudioOutput in tests).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "runtime/io/clock.hpp"
#include "base/result.hpp"

namespace seqc::audio {

// Samples to play: interleaved frames of `channels` (1 or 2) samples in [-1, 1].
struct PcmAudio {
  std::vector<float> samples;
  int channels = 1;
  double sample_rate = 0;
  std::int64_t frames() const {
    return channels > 0 ? static_cast<std::int64_t>(samples.size()) / channels : 0;
  }
};

// The playback clock, as the audio API reports it: at host instant `at`, frame `written` is the
// next to enter the API, and the API says it will be heard `latency` later. So frame 0 entered
// (the audio started) at at - written / rate and is heard `latency` after that.
struct PlaybackClock {
  io::TimePoint at{0};
  std::int64_t written = 0;
  io::Duration latency{0};
  double sample_rate = 0;
  // When frame 0 entered the output: the audio's start.
  io::TimePoint started() const;
  // The frame being heard at `at`.
  std::int64_t heard_frame() const;
};

class AudioOutput {
 public:
  virtual ~AudioOutput() = default;
  // Starts playing `audio` and returns once it plays and the API's clock can be read; an Error
  // says why not (no sound server, a refused format).
  virtual Status start(const PcmAudio& audio) = 0;
  // The playback clock now (after start()).
  virtual Result<PlaybackClock> clock() = 0;
  // True once every sample has been heard (or after stop()).
  virtual bool finished() = 0;
  // Stops at once (what is still buffered is dropped); harmless when not started.
  virtual void stop() = 0;
  // "PulseAudio (sink alsa_output.pci...)", for messages.
  virtual std::string describe() const = 0;
};

// Opens an output for one playback; an Error when no sound server can be reached.
class AudioOutputFactory {
 public:
  virtual ~AudioOutputFactory() = default;
  virtual Result<std::unique_ptr<AudioOutput>> open() = 0;
};

}  // namespace seqc::audio
