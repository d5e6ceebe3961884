// The audio-input boundary: samples read from a sound server's source or a file, each block
// dated on the host's monotonic clock (io::Clock's epoch), so what is heard in them (SMPTE
// timecode) can be placed in host time. `seqc follow --ltc` gets one passed in: PulseAudio
// (pulse_input.hpp) on a machine, a WAV file (wav_input.hpp) in tests and rehearsals.
#pragma once

#include <span>
#include <string>

#include "base/result.hpp"
#include "runtime/io/clock.hpp"

namespace seqc::audio {

struct InputBlock {
  std::size_t samples = 0;  // read into the buffer; 0: the input has ended
  // The host instant at which the block ended: when the sample after its last one was (or
  // would have been) captured. Sample k of the block was captured at
  // end_at - (samples - k) / sample_rate.
  io::TimePoint end_at{0};
};

class AudioInput {
 public:
  virtual ~AudioInput() = default;
  // Samples a second (fixed for the input's life).
  virtual double sample_rate() const = 0;
  // Waits for `into.size()` samples (mono: channels averaged) and returns how many it read:
  // fewer only where a file ends, 0 once it has ended. An Error when the source fails.
  virtual Result<InputBlock> read(std::span<float> into) = 0;
  // "PulseAudio source seqc_null.monitor", "ltc.wav", for messages.
  virtual std::string describe() const = 0;
};

}  // namespace seqc::audio
