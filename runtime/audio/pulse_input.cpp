#include "runtime/audio/pulse_input.hpp"

#include <pulse/error.h>
#include <pulse/simple.h>

#include <chrono>
#include <cmath>
#include <cstdint>

namespace seqc::audio {
namespace {

constexpr double kFragmentSeconds = 0.005;

class PulseAudioInput final : public AudioInput {
 public:
  PulseAudioInput(io::Clock& clock, pa_simple* pa, double rate, std::string name)
      : clock_(clock), pa_(pa), rate_(rate), name_(std::move(name)) {}
  PulseAudioInput(const PulseAudioInput&) = delete;
  PulseAudioInput& operator=(const PulseAudioInput&) = delete;
  ~PulseAudioInput() override { pa_simple_free(pa_); }

  double sample_rate() const override { return rate_; }

  Result<InputBlock> read(std::span<float> into) override {
    int error = 0;
    if (!into.empty() &&
        pa_simple_read(pa_, into.data(), into.size() * sizeof(float), &error) < 0) {
      return make_error("the sound server stopped recording: " + std::string(pa_strerror(error)));
    }
    const pa_usec_t latency = pa_simple_get_latency(pa_, &error);
    const io::TimePoint now = clock_.now();
    if (latency == static_cast<pa_usec_t>(-1)) {
      return make_error("the sound server gives no latency: " + std::string(pa_strerror(error)));
    }
    return InputBlock{into.size(), now - std::chrono::microseconds(latency)};
  }

  std::string describe() const override { return "PulseAudio source " + name_; }

 private:
  io::Clock& clock_;
  pa_simple* pa_;
  double rate_;
  std::string name_;
};

}  // namespace

Result<std::unique_ptr<AudioInput>> open_pulse_input(io::Clock& clock, const std::string& source,
                                                     double sample_rate,
                                                     const std::string& client_name) {
  if (!(sample_rate >= 1 && sample_rate <= 384000)) {
    return make_error("cannot record at " + std::to_string(std::lround(sample_rate)) + " Hz");
  }
  pa_sample_spec spec{};
  spec.format = PA_SAMPLE_FLOAT32NE;
  spec.rate = static_cast<std::uint32_t>(std::lround(sample_rate));
  spec.channels = 1;
  pa_buffer_attr attr{};
  attr.maxlength = static_cast<std::uint32_t>(-1);
  attr.tlength = static_cast<std::uint32_t>(-1);
  attr.prebuf = static_cast<std::uint32_t>(-1);
  attr.minreq = static_cast<std::uint32_t>(-1);
  attr.fragsize = static_cast<std::uint32_t>(sizeof(float) * kFragmentSeconds * spec.rate);
  const bool by_default = source.empty() || source == "default";
  const std::string name = by_default ? "(the default source)" : "\"" + source + "\"";
  int error = 0;
  pa_simple* pa = pa_simple_new(nullptr, client_name.c_str(), PA_STREAM_RECORD,
                                by_default ? nullptr : source.c_str(), "timecode", &spec, nullptr,
                                &attr, &error);
  if (pa == nullptr) {
    return make_error("cannot record from PulseAudio source " + name + ": " + pa_strerror(error));
  }
  return std::unique_ptr<AudioInput>(
      std::make_unique<PulseAudioInput>(clock, pa, spec.rate, by_default ? "default" : source));
}

}  // namespace seqc::audio
