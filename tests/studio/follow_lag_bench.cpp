// follow_lag_bench: how long from the page's scrub reaching the follower to the move reaching
// the controller, on the real clock. The follower is the studio's (make_robot_follower, with its
// thread) on io::SteadyClock, writing to the in-process xArm emulator at 9600 baud (emu:xarm);
// each write is stamped on the steady clock as it returns, and the move's own wire time at
// 9600 baud (10 bits a byte) is added, since the in-process line does not take it in real time.
//
//   follow_lag_bench [--scrubs N] [--gap-ms G]
// scrubs N times (default 200) to pseudo-random instants of a six-servo dance, G ms apart
// (default 50: each scrub finds the line free), then as fast as a dragged slider reports
// (16 ms apart: a scrub can find the line still busy with the last move and wait for it), and
// prints the median and the 99th percentile of each. No threshold: it prints what it measured.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "compiler/compile.hpp"
#include "runtime/boards/ports.hpp"
#include "runtime/studio/robot_follower.hpp"

namespace {

using namespace std::chrono_literals;
using seqc::io::Duration;
using seqc::io::TimePoint;

class OneFile final : public seqc::FileReader {
 public:
  explicit OneFile(std::string text) : text_(std::move(text)) {}
  seqc::Result<std::string> read(const std::string&) override { return text_; }

 private:
  std::string text_;
};

// Forwards to the emulator's transport and stamps each write on the steady clock as it returns.
class StampedLine final : public seqc::io::Transport {
 public:
  StampedLine(seqc::io::Transport& inner, seqc::io::Clock& clock) : inner_(inner), clock_(clock) {}
  seqc::Status write(seqc::ByteView bytes) override {
    seqc::Status s = inner_.write(bytes);
    const std::lock_guard lock(mutex_);
    stamps_.push_back({clock_.now(), bytes.size()});
    return s;
  }
  seqc::io::ReadResult read(std::span<std::uint8_t> buffer, TimePoint deadline) override {
    return inner_.read(buffer, deadline);
  }
  void discard_input() override { inner_.discard_input(); }
  std::string describe() const override { return inner_.describe(); }
  double seconds_per_byte() const override { return inner_.seconds_per_byte(); }

  struct Stamp {
    TimePoint at{0};
    std::size_t bytes = 0;
  };
  std::vector<Stamp> since(std::size_t from) {
    const std::lock_guard lock(mutex_);
    return {stamps_.begin() + static_cast<std::ptrdiff_t>(std::min(from, stamps_.size())),
            stamps_.end()};
  }
  std::size_t count() {
    const std::lock_guard lock(mutex_);
    return stamps_.size();
  }

 private:
  seqc::io::Transport& inner_;
  seqc::io::Clock& clock_;
  std::mutex mutex_;
  std::vector<Stamp> stamps_;
};

std::string dance() {
  std::string text =
      "robot: xarm\nsequence:\n"
      "  - move: {claw: 500, wrist_roll: 500, wrist_pitch: 500, elbow: 500, shoulder: 500, "
      "base: 500}\n    time: 500ms\n"
      "  - repeat: 8\n    do:\n";
  for (const char* to : {"300", "700"}) {
    text += std::string("      - move: {claw: ") + to + ", wrist_roll: " + to +
            ", wrist_pitch: " + to + ", elbow: " + to + ", shoulder: " + to + ", base: " + to +
            "}\n        time: 1000ms\n        ease: in-out\n";
  }
  return text;
}

double pct(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t rank =
      std::min(v.size() - 1,
               static_cast<std::size_t>(std::ceil(p / 100.0 * static_cast<double>(v.size()))) - 1);
  return v[rank];
}

// Lags (ms) of `scrubs` scrubs `gap` apart: report to the first write after it, plus its wire.
std::vector<double> measure(seqc::studio::PlayheadSink& sink, StampedLine& line,
                            seqc::io::Clock& clock, int scrubs, Duration gap, unsigned& seed) {
  std::vector<double> lags;
  for (int i = 0; i < scrubs; ++i) {
    seed = seed * 1103515245u + 12345u;
    const double ms = (seed >> 8) % 16000;
    const std::size_t before = line.count();
    const TimePoint asked = clock.now();
    sink.report({ms, seqc::studio::PlayheadMode::Scrubbed, false});
    // A scrub may wait for the line (the worker sends it) or send nothing (already there).
    const TimePoint give_up = asked + 200ms;
    std::vector<StampedLine::Stamp> after;
    while ((after = line.since(before)).empty() && clock.now() < give_up) {
      std::this_thread::sleep_for(200us);
    }
    if (!after.empty()) {
      const double wire_ms = static_cast<double>(after.front().bytes) * 10 * 1000 / 9600;
      lags.push_back(std::chrono::duration<double, std::milli>(after.front().at - asked).count() +
                     wire_ms);
    }
    clock.sleep_until(asked + gap);
  }
  return lags;
}

}  // namespace

int main(int argc, char** argv) {
  int scrubs = 200;
  int gap_ms = 50;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--scrubs") == 0) scrubs = std::atoi(argv[i + 1]);
    if (std::strcmp(argv[i], "--gap-ms") == 0) gap_ms = std::atoi(argv[i + 1]);
  }
  OneFile files(dance());
  const seqc::compiler::CompileOutput output = seqc::compiler::compile_file("dance.yaml", files);
  if (!output.servo_program()) {
    std::fprintf(stderr, "follow_lag_bench: the dance does not compile:\n%s",
                 seqc::render_all(output.diagnostics, output.sources).c_str());
    return 1;
  }
  seqc::io::SteadyClock clock;
  const seqc::boards::Board& board = *seqc::boards::find_board("xarm");
  seqc::boards::OpenResult opened = seqc::boards::open_port({"emu:xarm", &board}, clock);
  if (!opened.port || !opened.port->transport) {
    std::fprintf(stderr, "follow_lag_bench: emu:xarm did not open\n");
    return 1;
  }
  StampedLine line(*opened.port->transport, clock);
  unsigned seed = 1;
  std::vector<double> spaced, dragged;
  {
    auto sink = seqc::studio::make_robot_follower(board, line, clock);
    sink->set_program(output);
    spaced = measure(*sink, line, clock, scrubs, std::chrono::milliseconds(gap_ms), seed);
    dragged = measure(*sink, line, clock, scrubs, 16ms, seed);
    sink->stop();
  }
  std::printf("scrub -> move at the controller (write returned + its wire time at 9600 baud)\n");
  std::printf("  %d ms apart: %zu moves, median %.2f ms, p99 %.2f ms\n", gap_ms, spaced.size(),
              pct(spaced, 50), pct(spaced, 99));
  std::printf("  16 ms apart: %zu moves, median %.2f ms, p99 %.2f ms\n", dragged.size(),
              pct(dragged, 50), pct(dragged, 99));
  return spaced.empty() ? 1 : 0;
}
