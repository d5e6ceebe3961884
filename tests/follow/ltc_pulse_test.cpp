// The LTC show clock on a real sound server: libltc's 25 fps signal played into a null sink of
// its own (`pactl load-module module-null-sink`) and recorded from the sink's ".monitor" source
// through the PulseAudio input, on the host's monotonic clock. It must lock, start, and keep
// the timecode's time against the host's clock: every Sync's host instant minus its dance time
// stays within a few milliseconds of the first's. Run under tests/music/with_pulse.sh (a
// private server with a null sink when none runs).
#include <gtest/gtest.h>
#include <pulse/error.h>
#include <pulse/simple.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "runtime/audio/pulse_input.hpp"
#include "runtime/follow/ltc_clock.hpp"
#include "tests/follow/ltc_test_signals.hpp"

namespace seqc::follow {
namespace {

std::string command_output(const std::string& command) {
  std::string out;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return out;
  std::array<char, 256> line{};
  while (fgets(line.data(), static_cast<int>(line.size()), pipe) != nullptr) out += line.data();
  pclose(pipe);
  return out;
}

// A null sink for the length of the test, loaded into the server and unloaded after.
class NullSink {
 public:
  explicit NullSink(const std::string& name) {
    module_ = command_output("pactl load-module module-null-sink sink_name=" + name +
                             " rate=48000 norewinds=1 2>/dev/null");
    while (!module_.empty() && (module_.back() == '\n' || module_.back() == ' ')) {
      module_.pop_back();
    }
  }
  ~NullSink() {
    if (!module_.empty()) (void)command_output("pactl unload-module " + module_);
  }
  bool loaded() const { return !module_.empty(); }

 private:
  std::string module_;
};

// Plays `audio` into `sink` at a low latency (`latency_s` of buffer), from a thread, until done
// (`loop`: again and again until destroyed). Silence played first keeps a null sink rendering a
// few milliseconds ahead, as a sink that is playing does, instead of up to seconds ahead (see
// tests/music/pulse_harness.hpp).
class Player {
 public:
  Player(const audio::MonoAudio& audio, const std::string& sink, double latency_s, bool loop)
      : audio_(audio) {
    pa_sample_spec spec{};
    spec.format = PA_SAMPLE_FLOAT32NE;
    spec.rate = static_cast<std::uint32_t>(audio.sample_rate);
    spec.channels = 1;
    pa_buffer_attr attr{};
    attr.maxlength = static_cast<std::uint32_t>(-1);
    attr.tlength = static_cast<std::uint32_t>(sizeof(float) * audio.sample_rate * latency_s);
    attr.prebuf = static_cast<std::uint32_t>(-1);
    attr.minreq = static_cast<std::uint32_t>(-1);
    int err = 0;
    pa_ = pa_simple_new(nullptr, "seqc-test-ltc", PA_STREAM_PLAYBACK, sink.c_str(), "ltc", &spec,
                        nullptr, &attr, &err);
    if (pa_ == nullptr) {
      error = std::string("cannot play: ") + pa_strerror(err);
      return;
    }
    playing_ = std::thread([this, loop] {
      const std::size_t block = static_cast<std::size_t>(audio_.sample_rate * 0.002);
      int e = 0;
      do {
        for (std::size_t at = 0; at < audio_.samples.size() && !stop_; at += block) {
          const std::size_t n = std::min(block, audio_.samples.size() - at);
          if (pa_simple_write(pa_, audio_.samples.data() + at, n * sizeof(float), &e) < 0) return;
        }
      } while (loop && !stop_);
      if (!stop_) pa_simple_drain(pa_, &e);
    });
  }
  ~Player() {
    stop_ = true;
    if (playing_.joinable()) playing_.join();
    if (pa_ != nullptr) pa_simple_free(pa_);
  }
  std::string error;

 private:
  const audio::MonoAudio& audio_;
  pa_simple* pa_ = nullptr;
  std::atomic<bool> stop_{false};
  std::thread playing_;
};

double ms(io::Duration d) { return static_cast<double>(d.count()) / 1e6; }

TEST(LtcPulse, LocksAndKeepsTimeOnARealSoundServer) {
  const audio::MonoAudio audio = testing::read_ltc_signal("ltc-25-48000");
  ASSERT_EQ(audio.sample_rate, 48000) << "missing " << testing::ltc_signal_path("ltc-25-48000");
  NullSink sink("seqc_ltc_test");
  ASSERT_TRUE(sink.loaded()) << "pactl load-module module-null-sink failed";
  audio::MonoAudio silence;
  silence.sample_rate = 48000;
  silence.samples.assign(960, 0.0f);
  Player keep_alive(silence, "seqc_ltc_test", 0.004, true);
  ASSERT_EQ(keep_alive.error, "");
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  io::SteadyClock clock;
  auto input = audio::open_pulse_input(clock, "seqc_ltc_test.monitor", 48000, "seqc-test");
  ASSERT_TRUE(input.ok()) << input.error().message;
  LtcClockOptions options;
  options.start = {10, 0, 0, 0, false};
  auto ltc = LtcClock::create(std::move(*input), clock, options);
  ASSERT_TRUE(ltc.ok());

  const io::TimePoint played = clock.now();
  Player player(audio, "seqc_ltc_test", 0.02, false);
  ASSERT_EQ(player.error, "");
  std::vector<ShowClockEvent> events;
  std::vector<double> lag_ms;  // how long after its `at` each event was handed over
  const io::TimePoint give_up = played + std::chrono::seconds(8);
  while (clock.now() < give_up) {
    auto event = (*ltc)->next(give_up);
    if (!event) break;
    lag_ms.push_back(ms(clock.now() - event->at));
    events.push_back(*event);
    if (event->kind == ShowClockKind::Stop) break;
  }
  ASSERT_GE(events.size(), 3u);
  EXPECT_EQ(events[0].kind, ShowClockKind::Open);
  EXPECT_EQ(events[1].kind, ShowClockKind::Start);
  // Locked past --start: four frames heard.
  EXPECT_NEAR(events[1].dance_ms, 160, 1e-6);
  std::vector<double> offsets;
  std::size_t syncs = 0;
  for (std::size_t i = 1; i < events.size() && events[i].kind != ShowClockKind::Stop; ++i) {
    if (events[i].kind == ShowClockKind::Sync) ++syncs;
    offsets.push_back(ms(events[i].at - events[1].at) - (events[i].dance_ms - events[1].dance_ms));
  }
  // 74 frames are heard (the last one's end is not); lock on the fourth: 70 Syncs, give or
  // take one lost to the stream's start.
  EXPECT_GE(syncs, 68u);
  const auto [low, high] = std::minmax_element(offsets.begin(), offsets.end());
  std::printf(
      "[ ltc pulse ] locked %.1f ms after playing began; %zu Syncs; the timecode against "
      "the host clock moved %.2f..%.2f ms; events handed over %.1f-%.1f ms after their "
      "instant\n",
      ms(events[0].at - played), syncs, *low, *high,
      *std::min_element(lag_ms.begin(), lag_ms.end()),
      *std::max_element(lag_ms.begin(), lag_ms.end()));
  EXPECT_LT(*high - *low, 15.0);
  EXPECT_LT(ms(events[0].at - played), 1000.0);
  for (double lag : lag_ms) EXPECT_GE(lag, -1.0);  // never dated in the future
  ASSERT_EQ(events.back().kind, ShowClockKind::Stop);
  EXPECT_EQ(events.back().detail.rfind("no timecode since 10:00:02:23", 0), 0u)
      << events.back().detail;
}

}  // namespace
}  // namespace seqc::follow
