#include "runtime/audio/pulse_output.hpp"

#include <pulse/context.h>
#include <pulse/error.h>
#include <pulse/mainloop.h>
#include <pulse/simple.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <thread>
#include <vector>

namespace seqc::audio {
namespace {

constexpr double kBlockSeconds = 0.005;
constexpr double kBufferSeconds = 0.040;
constexpr double kSettleSeconds = 0.150;
constexpr std::size_t kReadingsToStart = 8;
constexpr std::size_t kReadingsKept = 16;

std::string pa_text(int error) { return pa_strerror(error); }

// Is a server there? A context connected and dropped: what pa_simple would meet, said early.
Status probe_server(const std::string& client_name) {
  pa_mainloop* loop = pa_mainloop_new();
  if (loop == nullptr) return make_error("cannot start the PulseAudio client");
  pa_context* context = pa_context_new(pa_mainloop_get_api(loop), client_name.c_str());
  Status status = Ok{};
  if (context == nullptr) {
    status = make_error("cannot start the PulseAudio client");
  } else if (pa_context_connect(context, nullptr, PA_CONTEXT_NOAUTOSPAWN, nullptr) < 0) {
    status =
        make_error("cannot connect to the sound server: " + pa_text(pa_context_errno(context)));
  } else {
    for (;;) {
      const pa_context_state_t state = pa_context_get_state(context);
      if (state == PA_CONTEXT_READY) break;
      if (!PA_CONTEXT_IS_GOOD(state)) {
        status =
            make_error("cannot connect to the sound server: " + pa_text(pa_context_errno(context)));
        break;
      }
      if (pa_mainloop_iterate(loop, 1, nullptr) < 0) {
        status = make_error("cannot connect to the sound server");
        break;
      }
    }
    pa_context_disconnect(context);
  }
  if (context != nullptr) pa_context_unref(context);
  pa_mainloop_free(loop);
  return status;
}

struct Reading {
  io::TimePoint at{0};
  std::int64_t written = 0;
  io::Duration latency{0};
};

}  // namespace

class PulseAudioOutput final : public AudioOutput {
 public:
  PulseAudioOutput(io::Clock& clock, std::string client_name)
      : clock_(clock), client_name_(std::move(client_name)) {}
  ~PulseAudioOutput() override { stop(); }

  Status start(const PcmAudio& audio) override {
    if (audio.channels < 1 || audio.channels > 2 || audio.sample_rate < 1) {
      return make_error("the audio output plays mono or stereo only");
    }
    audio_ = audio;
    pa_sample_spec spec{};
    spec.format = PA_SAMPLE_FLOAT32NE;
    spec.rate = static_cast<std::uint32_t>(std::lround(audio.sample_rate));
    spec.channels = static_cast<std::uint8_t>(audio.channels);
    const auto frame_bytes = static_cast<std::uint32_t>(sizeof(float)) * spec.channels;
    pa_buffer_attr attr{};
    attr.maxlength = static_cast<std::uint32_t>(-1);
    attr.tlength = frame_bytes * static_cast<std::uint32_t>(kBufferSeconds * spec.rate);
    attr.prebuf = static_cast<std::uint32_t>(-1);
    attr.minreq = static_cast<std::uint32_t>(-1);
    attr.fragsize = static_cast<std::uint32_t>(-1);
    int error = 0;
    pa_ = pa_simple_new(nullptr, client_name_.c_str(), PA_STREAM_PLAYBACK, nullptr, "song", &spec,
                        nullptr, &attr, &error);
    if (pa_ == nullptr) return make_error("cannot play on the sound server: " + pa_text(error));
    feeder_ = std::thread([this] { feed(); });
    std::unique_lock lock(mutex_);
    ready_.wait(lock, [this] { return readings_.size() >= kReadingsToStart || done_; });
    if (!failure_.empty()) return make_error(failure_);
    if (readings_.size() < kReadingsToStart) {
      return make_error("the song is too short to time its playback");
    }
    return Ok{};
  }

  Result<PlaybackClock> clock() override {
    std::lock_guard lock(mutex_);
    if (readings_.empty())
      return make_error(failure_.empty() ? "the audio has not started" : failure_);
    const double rate = audio_.sample_rate;
    // Each reading dates frame 0 as heard; the median of them is the clock's.
    std::vector<io::TimePoint> heard0;
    for (const Reading& r : readings_) {
      heard0.push_back(r.at + r.latency -
                       io::Duration{std::llround(static_cast<double>(r.written) * 1e9 / rate)});
    }
    std::nth_element(heard0.begin(), heard0.begin() + static_cast<long>(heard0.size() / 2),
                     heard0.end());
    const io::TimePoint median = heard0[heard0.size() / 2];
    const Reading& last = readings_.back();
    const io::Duration since_start{std::llround(static_cast<double>(last.written) * 1e9 / rate)};
    // Stated as the last reading with the latency that puts frame 0 at the median.
    return PlaybackClock{last.at, last.written, median + since_start - last.at, rate};
  }

  bool finished() override { return done_.load(); }

  void stop() override {
    stop_.store(true);
    if (feeder_.joinable()) feeder_.join();
    if (pa_ != nullptr) {
      int error = 0;
      pa_simple_flush(pa_, &error);
      pa_simple_free(pa_);
      pa_ = nullptr;
    }
    done_.store(true);
  }

  std::string describe() const override { return "the PulseAudio sound server"; }

 private:
  void fail(const std::string& why) {
    std::lock_guard lock(mutex_);
    failure_ = why;
  }

  void feed() {
    const auto channels = static_cast<std::size_t>(audio_.channels);
    const auto block = static_cast<std::size_t>(kBlockSeconds * audio_.sample_rate);
    const auto settle = static_cast<std::int64_t>(kSettleSeconds * audio_.sample_rate);
    const std::int64_t frames = audio_.frames();
    std::int64_t written = 0;
    int error = 0;
    while (!stop_.load() && written < frames) {
      const auto n = static_cast<std::size_t>(
          std::min<std::int64_t>(static_cast<std::int64_t>(block), frames - written));
      const float* from = audio_.samples.data() + static_cast<std::size_t>(written) * channels;
      if (pa_simple_write(pa_, from, n * channels * sizeof(float), &error) < 0) {
        fail("the sound server stopped playing: " + pa_text(error));
        break;
      }
      written += static_cast<std::int64_t>(n);
      const pa_usec_t latency = pa_simple_get_latency(pa_, &error);
      const io::TimePoint at = clock_.now();
      if (latency == static_cast<pa_usec_t>(-1)) {
        fail("the sound server gives no latency: " + pa_text(error));
        break;
      }
      if (written < settle) continue;
      std::lock_guard lock(mutex_);
      readings_.push_back({at, written, std::chrono::microseconds(latency)});
      if (readings_.size() > kReadingsKept) readings_.pop_front();
      if (readings_.size() >= kReadingsToStart) ready_.notify_all();
    }
    if (!stop_.load() && written >= frames) pa_simple_drain(pa_, &error);
    {
      std::lock_guard lock(mutex_);
      done_.store(true);
    }
    ready_.notify_all();
  }

  io::Clock& clock_;
  std::string client_name_;
  PcmAudio audio_;
  pa_simple* pa_ = nullptr;
  std::thread feeder_;
  std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<Reading> readings_;
  std::string failure_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> done_{false};
};

Result<std::unique_ptr<AudioOutput>> PulseAudioOutputFactory::open() {
  if (Status there = probe_server(client_name_); !there) return there.error();
  return std::unique_ptr<AudioOutput>(std::make_unique<PulseAudioOutput>(clock_, client_name_));
}

}  // namespace seqc::audio
