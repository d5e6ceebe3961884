// One real-time play over a pseudo-terminal: the player and SerialTransport on the slave side,
// the Raspblock emulator behind PtyServer on the master side (a thread, real clock). The board
// must receive exactly the compiled stream, and no packet before its time. How late packets
// land depends on the machine's load; that is measured by tests/bench/play_bench, not here.
#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "compiler/compile.hpp"
#include "compiler/targets/raspblock/raspblock_stream.hpp"
#include "runtime/emulator/pty_device.hpp"
#include "runtime/emulator/pty_server.hpp"
#include "runtime/player/player.hpp"
#include "runtime/transport/serial_transport.hpp"
#include "tests/first_read_clock.hpp"

namespace seqc::player {
namespace {

// Hands everything to the board and stops the server once `expected` bytes have arrived.
class StopWhenAllArrived final : public emu::PtyDevice {
 public:
  StopWhenAllArrived(emu::PtyDevice& inner, std::size_t expected, std::atomic<bool>& stop)
      : inner_(inner), expected_(expected), stop_(stop) {}
  void receive(ByteView bytes, io::TimePoint at) override {
    inner_.receive(bytes, at);
    received_ += bytes.size();
    if (received_ >= expected_) stop_ = true;
  }
  std::optional<io::TimePoint> next_output_at() const override { return inner_.next_output_at(); }
  Bytes take_output(io::TimePoint upto) override { return inner_.take_output(upto); }
  bool hung_up() const override { return inner_.hung_up(); }

 private:
  emu::PtyDevice& inner_;
  std::size_t expected_;
  std::size_t received_ = 0;
  std::atomic<bool>& stop_;
};

class OneFile final : public seqc::FileReader {
 public:
  explicit OneFile(std::string text) : text_(std::move(text)) {}
  Result<std::string> read(const std::string&) override { return text_; }

 private:
  std::string text_;
};

TEST(PlayerPty, TheBoardReceivesTheCompiledStreamOnTime) {
  OneFile file(
      "robot: raspblock\n"
      "sequence:\n"
      "  - move: home\n"
      "    time: 100ms\n"
      "  - drive: {x: 10}\n"
      "    move: {pan: 2000, tilt: 1200}\n"
      "    time: 600ms\n"
      "  - drive: {z: -100}\n"
      "    time: 300ms\n"
      "  - move: {servo2: 600}\n"
      "    time: 200ms\n");
  auto compiled = compiler::compile_file("car.yaml", file);
  ASSERT_NE(compiled.raspblock_program(), nullptr);
  const compiler::RaspblockProgram& program = *compiled.raspblock_program();
  auto frames = compiler::plan_stream(program);
  ASSERT_TRUE(frames.ok());

  auto server = emu::PtyServer::open(emu::PtyOptions{115200, std::nullopt});
  ASSERT_TRUE(server.ok()) << server.error().message;
  std::vector<ScheduledFrame> schedule;
  Bytes all;
  for (const auto& f : *frames) {
    schedule.push_back({std::chrono::milliseconds(f.at_ms), f.bytes});
    all.insert(all.end(), f.bytes.begin(), f.bytes.end());
  }

  emu::RaspblockEmulator board;
  emu::RaspblockPtyDevice device(board, nullptr);
  std::atomic<bool> stop{false};
  StopWhenAllArrived counted(device, all.size(), stop);
  seqc::testing::FirstReadClock server_clock;
  std::thread serving([&] { (void)server->serve(counted, server_clock, stop); });

  io::SteadyClock clock;
  PlayReport report;
  io::TimePoint play_start{};
  {
    transport::SerialOptions options;
    options.baud = 115200;
    auto link = transport::SerialTransport::open(server->slave_path(), clock, options);
    ASSERT_TRUE(link.ok()) << link.error().message;
    play_start = clock.now();
    report = play(schedule, **link, clock);
  }
  // The server stops by itself once every byte has arrived; a give-up guards only against a
  // lost byte, which the comparison below then reports.
  for (int i = 0; i < 10000 && !stop.load(); ++i) {
    clock.sleep_until(clock.now() + std::chrono::milliseconds(1));
  }
  stop = true;
  serving.join();

  EXPECT_EQ(report.end, PlayEnd::Completed);
  EXPECT_EQ(report.sent, schedule.size());
  EXPECT_EQ(board.received_bytes(), all);
  EXPECT_TRUE(board.rejections().empty());
  ASSERT_EQ(board.packets().size(), program.packets.size());
  for (std::size_t i = 0; i < program.packets.size(); ++i) {
    EXPECT_EQ(board.packets()[i].packet, program.packets[i].packet) << i;
    // Never early: the board read packet i no sooner than its time after play() began.
    const io::TimePoint arrived = server_clock.first() + board.packets()[i].at;
    const auto want = std::chrono::milliseconds(program.packets[i].at_ms);
    EXPECT_GE(arrived, play_start + want) << i;
  }
}

}  // namespace
}  // namespace seqc::player
