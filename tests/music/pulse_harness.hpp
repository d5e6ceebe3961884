// What the real-sound-server test and bench share: an xArm controller emulated at 9600 baud
// behind a pseudo-terminal (a thread on the host's clock), a stream of silence that keeps the
// sink rendering close to its time, and a recorder of the default sink's monitor that dates the
// first sample of a click as it leaves the sink, on the host's monotonic clock. Run them under
// tests/music/with_pulse.sh, which starts a PulseAudio server with a null sink when none is
// running.
//
// The recorder reads blocks of 2 ms through pa_simple; after each read, pa_simple_get_latency
// says how long ago the next sample to be read was captured, so sample k of the block just read
// left the sink at now - latency - (samples after it in the block) / rate. A null sink renders a
// block ahead of its time and its monitor hands it over at once (the latency then reads 0): the
// instant measured is when the sample left the sink, up to one block (a few ms with
// SinkKeepAlive) before the sink's own time for it. A recorder woken late dates the click late
// by as much. (Dating one read and counting samples from it was tried: over a 30 s recording
// it drifted by about 0.5 ms a second against the host's clock.)
#pragma once

#include <pulse/error.h>
#include <pulse/simple.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "runtime/audio/audio_files.hpp"
#include "runtime/emulator/pty_device.hpp"
#include "runtime/emulator/pty_server.hpp"
#include "runtime/emulator/xarm_emulator.hpp"
#include "runtime/io/clock.hpp"
#include "tests/first_read_clock.hpp"

namespace seqc::test {

// An xArm controller at 9600 baud on a pseudo-terminal, served until destroyed.
class PtyController {
 public:
  PtyController() : device_(emulator_) {
    auto server = emu::PtyServer::open(emu::PtyOptions{9600, std::nullopt});
    if (!server) {
      error = server.error().message;
      return;
    }
    server_.emplace(std::move(*server));
    serving_ = std::thread([this] { (void)server_->serve(device_, clock_, stop_); });
    while (clock_.first() == io::TimePoint{-1}) std::this_thread::yield();
  }
  ~PtyController() { stop(); }
  void stop() {
    stop_ = true;
    if (serving_.joinable()) serving_.join();
  }
  std::string path() const { return server_ ? server_->slave_path() : std::string(); }
  // When the frame `raw` last reached the controller, on the host's clock (after stop()).
  std::optional<io::TimePoint> arrival(const Bytes& raw) const {
    std::optional<io::TimePoint> at;
    for (const emu::ReceivedFrame& f : emulator_.received()) {
      if (f.raw == raw) at = clock_.first() + f.at;
    }
    return at;
  }
  // Every arrival of `raw`, in order (after stop()).
  std::vector<io::TimePoint> arrivals(const Bytes& raw) const {
    std::vector<io::TimePoint> at;
    for (const emu::ReceivedFrame& f : emulator_.received()) {
      if (f.raw == raw) at.push_back(clock_.first() + f.at);
    }
    return at;
  }
  std::string error;

 private:
  static emu::XArmConfig paced() {
    emu::XArmConfig c;
    c.baud = 9600;
    return c;
  }
  emu::XArmEmulator emulator_{paced()};
  emu::ControllerPtyDevice device_;
  seqc::testing::FirstReadClock clock_;
  std::atomic<bool> stop_{false};
  std::optional<emu::PtyServer> server_;
  std::thread serving_;
};

// A stream of silence at 4 ms of latency on the default sink for as long as it lives. A sink
// with nothing to play (a null sink especially) renders up to seconds ahead, and when a stream
// then arrives it rewinds what its monitor has already been handed; with this stream playing
// first, the sink renders a few milliseconds ahead, as a desktop sink that is playing does.
class SinkKeepAlive {
 public:
  explicit SinkKeepAlive(double rate) : rate_(rate) {
    pa_sample_spec spec{};
    spec.format = PA_SAMPLE_FLOAT32NE;
    spec.rate = static_cast<std::uint32_t>(rate);
    spec.channels = 1;
    pa_buffer_attr attr{};
    attr.maxlength = static_cast<std::uint32_t>(-1);
    attr.tlength = static_cast<std::uint32_t>(sizeof(float) * rate * 0.004);
    attr.prebuf = static_cast<std::uint32_t>(-1);
    attr.minreq = static_cast<std::uint32_t>(-1);
    int err = 0;
    pa_ = pa_simple_new(nullptr, "seqc-test-keepalive", PA_STREAM_PLAYBACK, nullptr, "silence",
                        &spec, nullptr, &attr, &err);
    if (pa_ == nullptr) {
      error = std::string("cannot play silence: ") + pa_strerror(err);
      return;
    }
    playing_ = std::thread([this] {
      const std::vector<float> silence(static_cast<std::size_t>(rate_ * 0.002), 0.0f);
      int e = 0;
      while (!stop_) {
        if (pa_simple_write(pa_, silence.data(), silence.size() * sizeof(float), &e) < 0) return;
      }
    });
    // Long enough for the sink to take the lower latency.
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
  }
  ~SinkKeepAlive() {
    stop_ = true;
    if (playing_.joinable()) playing_.join();
    if (pa_ != nullptr) pa_simple_free(pa_);
  }
  std::string error;

 private:
  double rate_;
  pa_simple* pa_ = nullptr;
  std::atomic<bool> stop_{false};
  std::thread playing_;
};

// Records the default sink's monitor and dates every click (a sample above `threshold` after
// at least `quiet` of silence) as it left the sink.
class MonitorRecorder {
 public:
  explicit MonitorRecorder(double rate, double threshold = 0.1, double quiet_seconds = 0.2)
      : rate_(rate), threshold_(threshold), quiet_(static_cast<long>(quiet_seconds * rate)) {
    pa_sample_spec spec{};
    spec.format = PA_SAMPLE_FLOAT32NE;
    spec.rate = static_cast<std::uint32_t>(rate);
    spec.channels = 1;
    pa_buffer_attr attr{};
    attr.maxlength = static_cast<std::uint32_t>(-1);
    attr.fragsize = static_cast<std::uint32_t>(sizeof(float) * rate * 0.002);
    int err = 0;
    pa_ = pa_simple_new(nullptr, "seqc-test-monitor", PA_STREAM_RECORD, "@DEFAULT_MONITOR@",
                        "monitor", &spec, nullptr, &attr, &err);
    if (pa_ == nullptr) {
      error = std::string("cannot record the monitor: ") + pa_strerror(err);
      return;
    }
    reading_ = std::thread([this] { read(); });
  }
  ~MonitorRecorder() { stop(); }
  void stop() {
    stop_ = true;
    if (reading_.joinable()) reading_.join();
    if (pa_ != nullptr) pa_simple_free(pa_);
    pa_ = nullptr;
  }
  // When each click left the sink, in order (read after stop(), or while running: the vector
  // only grows in read()).
  std::vector<io::TimePoint> clicks() const {
    std::vector<io::TimePoint> copy;
    const std::size_t n = count_.load();
    copy.assign(clicks_.begin(), clicks_.begin() + static_cast<long>(n));
    return copy;
  }
  std::size_t click_count() const { return count_.load(); }
  std::string error;

 private:
  void read() {
    io::SteadyClock clock;
    const auto block = static_cast<std::size_t>(rate_ * 0.002);
    std::vector<float> samples(block);
    clicks_.reserve(1024);
    long silent = quiet_;
    int err = 0;
    while (!stop_) {
      if (pa_simple_read(pa_, samples.data(), block * sizeof(float), &err) < 0) return;
      const pa_usec_t latency = pa_simple_get_latency(pa_, &err);
      const io::TimePoint now = clock.now();
      for (std::size_t k = 0; k < block; ++k) {
        if (std::fabs(samples[k]) <= threshold_) {
          ++silent;
          continue;
        }
        if (silent >= quiet_ && clicks_.size() < clicks_.capacity()) {
          const double after = static_cast<double>(block - k) / rate_;
          clicks_.push_back(now - std::chrono::microseconds(latency) -
                            io::Duration{std::llround(after * 1e9)});
          count_.store(clicks_.size());
        }
        silent = 0;
      }
    }
  }

  double rate_;
  double threshold_;
  long quiet_;
  pa_simple* pa_ = nullptr;
  std::atomic<bool> stop_{false};
  std::thread reading_;
  std::vector<io::TimePoint> clicks_;
  std::atomic<std::size_t> count_{0};
};

// A song of `seconds` at `rate`: silence, and from `click` on a 20 ms burst at half scale.
inline audio::MonoAudio click_song(double rate, double seconds, double click) {
  audio::MonoAudio song;
  song.sample_rate = rate;
  song.samples.assign(static_cast<std::size_t>(seconds * rate), 0.0f);
  const auto from = static_cast<std::size_t>(std::llround(click * rate));
  for (std::size_t i = from; i < from + static_cast<std::size_t>(0.02 * rate); ++i) {
    song.samples[i] = (i - from) % 2 == 0 ? 0.5f : -0.5f;
  }
  return song;
}

}  // namespace seqc::test
