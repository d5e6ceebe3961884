// AudioInput from a PulseAudio source (libpulse-simple, PA_STREAM_RECORD; PipeWire's pulse
// server answers the same way): a microphone or line input, or a sink's ".monitor".
//
// Mono float samples at the rate asked (the server converts). Blocks are read through
// pa_simple_read and dated with pa_simple_get_latency, the server's own figure for how long ago
// the next sample to read was captured: the block just read ended `latency` before the read
// returned. The server buffers about 5 ms a fragment.
#pragma once

#include <memory>
#include <string>

#include "runtime/audio/audio_input.hpp"

namespace seqc::audio {

// Records from `source` ("default", or "" for the server's default source) at `sample_rate`.
// `clock` must be the host's monotonic clock (io::SteadyClock). An Error says why not: "cannot
// record from PulseAudio source \"x\": No such entity".
Result<std::unique_ptr<AudioInput>> open_pulse_input(io::Clock& clock, const std::string& source,
                                                     double sample_rate,
                                                     const std::string& client_name);

}  // namespace seqc::audio
