#include "runtime/audio/wav_input.hpp"

#include <sndfile.h>

#include <chrono>
#include <cmath>
#include <optional>
#include <vector>

namespace seqc::audio {
namespace {

constexpr int kMaxChannels = 64;

class WavInput final : public AudioInput {
 public:
  WavInput(SNDFILE* file, const SF_INFO& info, std::string path, io::Clock& clock, WavPace pace)
      : file_(file),
        channels_(info.channels),
        rate_(info.samplerate),
        path_(std::move(path)),
        clock_(clock),
        pace_(pace) {}
  WavInput(const WavInput&) = delete;
  WavInput& operator=(const WavInput&) = delete;
  ~WavInput() override { sf_close(file_); }

  double sample_rate() const override { return rate_; }

  Result<InputBlock> read(std::span<float> into) override {
    if (!started_) {
      started_ = clock_.now();
    }
    std::size_t got = 0;
    if (!ended_ && !into.empty()) {
      frames_.resize(into.size() * static_cast<std::size_t>(channels_));
      const sf_count_t n =
          sf_readf_float(file_, frames_.data(), static_cast<sf_count_t>(into.size()));
      if (n < 0) return make_error(path_ + ": " + sf_strerror(file_));
      got = static_cast<std::size_t>(n);
      for (std::size_t i = 0; i < got; ++i) {
        float sum = 0;
        for (int c = 0; c < channels_; ++c) {
          sum += frames_[i * static_cast<std::size_t>(channels_) + static_cast<std::size_t>(c)];
        }
        into[i] = sum / static_cast<float>(channels_);
      }
      if (got < into.size()) ended_ = true;
    }
    position_ += static_cast<std::int64_t>(got);
    const io::TimePoint end_at =
        *started_ + io::Duration{std::llround(static_cast<double>(position_) * 1e9 / rate_)};
    if (pace_ == WavPace::RealTime) clock_.sleep_until(end_at);
    return InputBlock{got, end_at};
  }

  std::string describe() const override { return path_; }

 private:
  SNDFILE* file_;
  int channels_;
  double rate_;
  std::string path_;
  io::Clock& clock_;
  WavPace pace_;
  std::optional<io::TimePoint> started_;
  std::int64_t position_ = 0;
  bool ended_ = false;
  std::vector<float> frames_;
};

}  // namespace

Result<std::unique_ptr<AudioInput>> open_wav_input(const std::string& path, io::Clock& clock,
                                                   WavPace pace) {
  SF_INFO info{};
  SNDFILE* file = sf_open(path.c_str(), SFM_READ, &info);
  if (file == nullptr) return make_error(path + ": " + sf_strerror(nullptr));
  if (info.channels < 1 || info.channels > kMaxChannels) {
    sf_close(file);
    return make_error(path + ": " + std::to_string(info.channels) + " channels (at most " +
                      std::to_string(kMaxChannels) + ")");
  }
  if (info.samplerate < 1) {
    sf_close(file);
    return make_error(path + ": no sample rate");
  }
  return std::unique_ptr<AudioInput>(std::make_unique<WavInput>(file, info, path, clock, pace));
}

}  // namespace seqc::audio
