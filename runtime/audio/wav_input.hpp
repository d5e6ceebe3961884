// AudioInput from a sound file (libsndfile: WAV and whatever else it reads), streamed in the
// blocks asked for, channels averaged; memory is one block whatever the file's length. A
// recording of timecode then plays as if heard live.
//
// The file's first sample is dated at the instant of the first read (on the clock given) and
// sample n at that instant + n / rate. RealTime sleeps on the clock until each block's end
// (with io::ManualClock, that moves the clock: a test runs an hour of signal in milliseconds,
// every date exact); Unpaced returns at once with the same dates.
#pragma once

#include <memory>
#include <string>

#include "runtime/audio/audio_input.hpp"

namespace seqc::audio {

enum class WavPace { RealTime, Unpaced };

// An Error names the path and what is wrong: no such file, not a sound file, more than 64
// channels, a sample rate below 1 Hz.
Result<std::unique_ptr<AudioInput>> open_wav_input(const std::string& path, io::Clock& clock,
                                                   WavPace pace);

}  // namespace seqc::audio
