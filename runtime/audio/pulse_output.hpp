// AudioOutput on a PulseAudio sound server (libpulse, LGPL, linked dynamically; PipeWire's
// pulse server answers the same way). The server is the one libpulse finds itself: PULSE_SERVER,
// else the user's socket.
//
// The samples are written by a thread through pa_simple in blocks of about 5 ms into a buffer of
// about 40 ms. After each write the thread reads the host clock and pa_simple_get_latency (the
// API's own figure: how long until the next sample written is heard), which dates frame 0 as
// heard at now + latency - written / rate. Readings from the first 150 ms (the server still
// prebuffering, the sink settling) are not used; start() returns once eight more have been
// taken, and clock() gives the median of the last 16, so one late wake-up of the thread does
// not move the clock.
#pragma once

#include <memory>
#include <string>

#include "runtime/audio/audio_output.hpp"

namespace seqc::audio {

class PulseAudioOutput;

class PulseAudioOutputFactory final : public AudioOutputFactory {
 public:
  // `clock` must be the host's monotonic clock (io::SteadyClock): the readings are dated on it.
  PulseAudioOutputFactory(io::Clock& clock, std::string client_name)
      : clock_(clock), client_name_(std::move(client_name)) {}
  // Connects to the server once to see that it is there ("cannot connect to the sound server:
  // Connection refused"), then hands out an output that connects again when started.
  Result<std::unique_ptr<AudioOutput>> open() override;

 private:
  io::Clock& clock_;
  std::string client_name_;
};

}  // namespace seqc::audio
