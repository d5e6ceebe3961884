// clock_bench: a long song on a board whose clock is off. A 4-minute dance (480 one-beat moves at
// 120 bpm, 240 s) is compiled, uploaded to the in-process xArm emulator with the `clock` fault
// (default +1 % and -1 %) and played once; the drift is how far the group's end (its finish
// notice) lands from 240 s of host time (target before: about 2.4 s, 240 s x 1 %). Then
// `seqc calibrate clock`'s measurement (boards::measure_clock: --runs 20 s runs) is taken
// against the same emulator, the dance recompiled with the measured ppm
// (CompileOptions::clock_ppm), uploaded and played again: the drift after (target <= 10 ms).
// Last, without calibration, `--resync 8`: the dance cut every 8 bars (16 s) into groups the
// computer starts at their bar lines, so only the last piece drifts (about 160 ms at 1 %).
// Everything runs in emulated time at 9600 baud, so the bench takes well under a second.
//
// Usage: clock_bench [--clock ERR]... [--runs N]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "compiler/compile.hpp"
#include "runtime/boards/board.hpp"
#include "runtime/boards/clock_calibration.hpp"
#include "runtime/boards/resync_run.hpp"
#include "runtime/emulator/board_clock.hpp"
#include "runtime/emulator/emulator_transport.hpp"
#include "runtime/emulator/xarm_emulator.hpp"
#include "runtime/upload/controller_link.hpp"

namespace {

using namespace seqc;

class OneFile final : public seqc::FileReader {
 public:
  explicit OneFile(std::string text) : text_(std::move(text)) {}
  Result<std::string> read(const std::string&) override { return text_; }

 private:
  std::string text_;
};

// 480 beats at 120 bpm = 240 s: the base and the elbow back and forth on every beat.
std::string dance() {
  return "robot: xarm\ntempo: 120\nmeter: 4/4\nsequence:\n"
         "  - repeat: 240\n    do:\n"
         "      - move: {base: 600, elbow: 450}\n        time: 1b\n"
         "      - move: {base: 400, elbow: 550}\n        time: 1b\n";
}

constexpr double kSongMs = 240000;

struct Played {
  bool ok = false;
  double lasted_ms = 0;
  std::size_t actions = 0;
};

// Compiles the dance for a clock `ppm` fast, stores it in group 0 and times one run.
Played play(const boards::Board& board, const boards::Line& line, std::int32_t ppm) {
  Played p;
  OneFile file(dance());
  compiler::CompileOptions options;
  options.clock_ppm = ppm;
  const compiler::CompileOutput out = compiler::compile_file("dance.yaml", file, options);
  if (out.servo_program() == nullptr) {
    std::fprintf(stderr, "the dance does not compile\n");
    return p;
  }
  p.actions = out.servo_program()->keyframes.size();
  auto plan = boards::plan_for(board, out, 0);
  if (!plan) return p;
  upload::UploadOptions upload_options;
  if (!boards::upload(board, line, *plan, upload_options, nullptr).ok()) return p;
  const boards::TimedRun run =
      board.time_run(line, 0, std::chrono::milliseconds(static_cast<int>(kSongMs * 1.3)));
  if (!run.ok()) return p;
  p.ok = true;
  p.lasted_ms = std::chrono::duration<double, std::milli>(run.lasted).count();
  return p;
}

// Resync every `bars` bars, uncalibrated: the host time from the first start to the last
// piece's finish notice, less the line's time for the last start (GroupStop + GroupRun, 11
// bytes) and for the notice (7 bytes), each 10 bits at 9600 baud.
std::optional<double> play_resynced(const boards::Board& board, const boards::Line& line,
                                    std::uint32_t bars, std::size_t& pieces_out) {
  OneFile file(dance());
  const compiler::CompileOutput out = compiler::compile_file("dance.yaml", file, {});
  if (out.servo_program() == nullptr) return std::nullopt;
  auto pieces = compiler::split_at_bars(*out.servo_program(), bars);
  if (!pieces) return std::nullopt;
  pieces_out = pieces->size();
  const boards::ResyncRun r = boards::store_and_start(board, line, out, *pieces, 10, {}, nullptr);
  if (!r.stored() || r.play.end != player::PlayEnd::Completed) return std::nullopt;
  upload::ControllerLink link(line.transport, line.clock);
  const auto last = static_cast<std::uint8_t>(10 + pieces->size() - 1);
  const auto w = link.wait_for(
      [last](const lsc::Reply& reply) {
        const auto* f = std::get_if<lsc::GroupFinished>(&reply);
        return f != nullptr && f->group == last ? upload::Verdict::Take : upload::Verdict::Skip;
      },
      line.clock.now() + std::chrono::seconds(60));
  if (!w.ok()) return std::nullopt;
  const double line_ms = 18 * 10 * 1000.0 / 9600;
  return std::chrono::duration<double, std::milli>(line.clock.now() - r.play.started).count() -
         line_ms;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> clocks;
  std::size_t runs = 5;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--clock") == 0 && i + 1 < argc) {
      clocks.emplace_back(argv[++i]);
    } else if (std::strcmp(argv[i], "--runs") == 0 && i + 1 < argc) {
      runs = std::strtoull(argv[++i], nullptr, 10);
    } else {
      std::fprintf(stderr, "usage: clock_bench [--clock ERR]... [--runs N]\n");
      return 2;
    }
  }
  if (clocks.empty()) clocks = {"+1%", "-1%"};
  const boards::Board* board = boards::find_board("xarm");
  if (board == nullptr) return 1;
  int status = 0;
  const auto wall_start = std::chrono::steady_clock::now();
  std::printf("a 240 s dance (480 one-beat moves), xArm emulator at 9600 baud, emulated time\n");
  for (const std::string& clock : clocks) {
    emu::XArmConfig config;
    config.baud = 9600;
    if (auto ok = emu::apply_emulator_options("clock=" + clock, config); !ok) {
      std::fprintf(stderr, "%s\n", ok.error().message.c_str());
      return 2;
    }
    emu::XArmEmulator emulator(config);
    io::ManualClock time;
    emu::EmulatorTransport transport(emulator, time);
    const boards::Line line{transport, time, nullptr, std::chrono::seconds(1)};

    const Played before = play(*board, line, 0);
    boards::ClockSettings settings;
    settings.group = 254;
    settings.runs = runs;
    const boards::ClockMeasurement m = boards::measure_clock(*board, line, settings);
    if (!before.ok || !m.ok()) {
      std::printf("clock %s: the emulated run failed\n", clock.c_str());
      status = 1;
      continue;
    }
    const auto ppm = static_cast<std::int32_t>(std::lround(m.mean_ppm));
    const Played after = play(*board, line, ppm);
    if (!after.ok) {
      std::printf("clock %s: the recompiled run failed\n", clock.c_str());
      status = 1;
      continue;
    }
    const double drift_before = before.lasted_ms - kSongMs;
    const double drift_after = after.lasted_ms - kSongMs;
    const bool met = std::abs(drift_after) <= 10.0;
    std::printf(
        "clock %s (%s):\n"
        "  before: %zu actions, the group ends at %.3f s: drift %+.1f ms (expected %+.1f ms)\n"
        "  calibrate: %+.1f ppm +- %.1f (%zu runs of %.3f s) -> --clock-ppm %+d\n"
        "  after:  %zu actions, the group ends at %.3f s: drift %+.3f ms (target <= 10 ms: %s)\n",
        clock.c_str(), emu::format_clock_error(config.faults.clock_ppm).c_str(), before.actions,
        before.lasted_ms / 1000, drift_before,
        kSongMs / (1 + config.faults.clock_ppm / 1e6) - kSongMs, m.mean_ppm, m.spread_ppm,
        m.ppm.size(), settings.run_ms / 1000.0, ppm, after.actions, after.lasted_ms / 1000,
        drift_after, met ? "met" : "NOT met");
    if (!met) status = 1;

    emu::XArmEmulator fresh(config);
    io::ManualClock fresh_time;
    emu::EmulatorTransport fresh_transport(fresh, fresh_time);
    const boards::Line fresh_line{fresh_transport, fresh_time, nullptr, std::chrono::seconds(1)};
    std::size_t pieces = 0;
    const auto resynced = play_resynced(*board, fresh_line, 8, pieces);
    if (!resynced) {
      std::printf("  resync: the emulated run failed\n");
      status = 1;
      continue;
    }
    std::printf(
        "  --resync 8, uncalibrated: %zu pieces of 16 s, the last ends at %.3f s: drift %+.1f "
        "ms (expected %+.1f ms, the last piece's alone)\n",
        pieces, *resynced / 1000, *resynced - kSongMs,
        16000 / (1 + config.faults.clock_ppm / 1e6) - 16000);
  }
  std::printf("wall time: %.2f s\n",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count());
  return status;
}
