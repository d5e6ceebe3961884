// Runs seqc subcommands in-process, the way main() does, against one emulated servo
// controller (`--port emu:xarm` bound to it through Context::hooks) on a ManualClock,
// with string streams for stdout and stderr. Expected request bytes in these tests are written
// by hand from docs/protocol/servo-controller.md, never produced by the project's encoder.
#pragma once

#include <gtest/gtest.h>

#include <atomic>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "runtime/cli/app.hpp"
#include "runtime/cli/context.hpp"
#include "runtime/emulator/lsc6_emulator.hpp"
#include "runtime/emulator/xarm_emulator.hpp"
#include "runtime/io/clock.hpp"
#include "base/bytes.hpp"

namespace seqc::cli::test {

// Files by path, for commands that read a choreography.
class MemoryFiles final : public seqc::FileReader {
 public:
  void add(std::string path, std::string text) { files_[std::move(path)] = std::move(text); }
  Result<std::string> read(const std::string& path) override {
    auto it = files_.find(path);
    if (it == files_.end()) return make_error("no such file");
    return it->second;
  }

 private:
  std::map<std::string, std::string> files_;
};

struct RunResult {
  int code = -1;
  std::string out;
  std::string err;
};

// `seqc ARGS` in-process, the way main() runs it, with string streams for stdout and stderr;
// `prepare` binds the Context to the test's emulators before the command runs.
template <class Prepare>
RunResult run_seqc(std::vector<std::string> args, io::Clock& clock, seqc::FileReader& files,
                   Prepare prepare) {
  args.insert(args.begin(), "seqc");
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());
  std::ostringstream out;
  std::ostringstream err;
  Context ctx{out, err, clock, files};
  prepare(ctx);
  RunResult r;
  r.code = cli::run(static_cast<int>(argv.size()), argv.data(), ctx);
  r.out = out.str();
  r.err = err.str();
  return r;
}

// Both storing dialects at once, on one ManualClock: `--port emu:xarm` is an xArm-family
// controller and `--port emu:lsc6` an LSC-6 board, each with default settings; `Files` is how
// the commands read files (MemoryFiles, or the disk for the project's examples).
template <class Files>
struct TwoBoards {
  io::ManualClock clock;
  emu::XArmEmulator xarm{emu::XArmConfig{}};
  emu::Lsc6Emulator lsc6{emu::Lsc6Config{}};
  Files files;
  std::atomic<bool> interrupted{false};

  RunResult run(std::vector<std::string> args) {
    return run_seqc(std::move(args), clock, files, [this](Context& ctx) {
      ctx.interrupted = &interrupted;
      ctx.hooks.xarm = &xarm;
      ctx.hooks.lsc6 = &lsc6;
      ctx.hooks.emulated_clock = &clock;
    });
  }
};

// An xArm emulator whose servo 6 (the base) starts at `position`, for first-move checks.
inline emu::XArmConfig base_at(std::uint16_t position) {
  emu::XArmConfig config;
  config.initial_positions.push_back({6, position});
  return config;
}

class DeviceHarness {
 public:
  explicit DeviceHarness(emu::XArmConfig config = {}) : emu(config) {}

  RunResult run(std::vector<std::string> args) {
    return run_seqc(std::move(args), clock, files, [this](Context& ctx) {
      ctx.interrupted = &interrupted;
      ctx.hooks.xarm = &emu;
      ctx.hooks.emulated_clock = &clock;
      ctx.in = in;
      ctx.audio_files = audio_files;
      ctx.audio_output = audio_output;
      ctx.scheduler = scheduler;
    });
  }

  std::istream* in = nullptr;  // the command's standard input, when it reads one
  // --music: where songs are decoded and played (null: none given).
  audio::AudioReader* audio_files = nullptr;
  audio::AudioOutputFactory* audio_output = nullptr;
  // --realtime: what raises the timing thread (null: the system's).
  io::Scheduler* scheduler = nullptr;

  // What the emulated controller received since the last mark() (or ever), as lowercase hex.
  std::string received() const {
    const Bytes all = emu.received_bytes();
    return to_hex(ByteView(all).subspan(mark_));
  }
  void mark() { mark_ = emu.received_bytes().size(); }

  // Stores group 3 = one action (1000 ms, servo 1 to 500) through the download handshake,
  // frames written by hand from docs/protocol/servo-controller.md, then mark()s.
  void store_group_3() {
    const char* frames[] = {"55 55 05 05 01 03 01", "55 55 07 05 02 03 00 01 00",
                            "55 55 06 05 03 03 00 00", "55 55 0c 05 04 03 00 00 0b e8 03 01 f4 01",
                            "55 55 04 05 05 03"};
    io::TimePoint t = clock.now();
    for (const char* f : frames) {
      emu.receive(*parse_hex(f), t);
      t += std::chrono::milliseconds(100);  // longer than the emulated flash erase
      (void)emu.take_output(t);
    }
    clock.sleep_until(t);
    ASSERT_TRUE(emu.stored_group(3).has_value());
    mark();
  }

  io::ManualClock clock;
  emu::XArmEmulator emu;
  MemoryFiles files;
  std::atomic<bool> interrupted{false};

 private:
  std::size_t mark_ = 0;
};

// Lowercase hex with single spaces, from hand-written text in any case and spacing.
inline std::string hex(std::string_view text) {
  auto b = parse_hex(text);
  EXPECT_TRUE(b.ok()) << text;
  return b.ok() ? to_hex(*b) : std::string();
}

// The confirmation every unanswered command is followed by: GetBatteryVoltage.
inline constexpr const char* kBatteryCheck = "55 55 02 0f";

}  // namespace seqc::cli::test
