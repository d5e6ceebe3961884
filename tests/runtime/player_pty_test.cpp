// One real-time play over a pseudo-terminal: the player and SerialTransport on the slave side,
// the Raspblock emulator behind PtyServer on the master side (a thread, real clock). The board
// must receive exactly the compiled stream, each packet close to its send time.
#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "compiler/backend/raspblock_stream.hpp"
#include "compiler/compile.hpp"
#include "runtime/emulator/pty_device.hpp"
#include "runtime/emulator/pty_server.hpp"
#include "runtime/player/player.hpp"
#include "runtime/transport/serial_transport.hpp"

namespace seqc::player {
namespace {

class OneFile final : public compiler::FileReader {
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
  auto frames = backend::plan_stream(program);
  ASSERT_TRUE(frames.ok());

  auto server = emu::PtyServer::open(emu::PtyOptions{115200, std::nullopt});
  ASSERT_TRUE(server.ok()) << server.error().message;
  emu::RaspblockEmulator board;
  emu::RaspblockPtyDevice device(board, nullptr);
  io::SteadyClock clock;
  std::atomic<bool> stop{false};
  std::thread serving([&] { (void)server->serve(device, clock, stop); });

  std::vector<ScheduledFrame> schedule;
  Bytes all;
  for (const auto& f : *frames) {
    schedule.push_back({std::chrono::milliseconds(f.at_ms), f.bytes});
    all.insert(all.end(), f.bytes.begin(), f.bytes.end());
  }
  PlayReport report;
  {
    transport::SerialOptions options;
    options.baud = 115200;
    auto link = transport::SerialTransport::open(server->slave_path(), clock, options);
    ASSERT_TRUE(link.ok()) << link.error().message;
    report = play(schedule, **link, clock);
  }
  clock.sleep_until(clock.now() + std::chrono::milliseconds(200));  // let the last bytes land
  stop = true;
  serving.join();

  EXPECT_EQ(report.end, PlayEnd::Completed);
  EXPECT_EQ(report.sent, schedule.size());
  EXPECT_EQ(board.received_bytes(), all);
  EXPECT_TRUE(board.rejections().empty());
  ASSERT_EQ(board.packets().size(), program.packets.size());
  const io::TimePoint first = board.packets().front().at;
  for (std::size_t i = 0; i < program.packets.size(); ++i) {
    EXPECT_EQ(board.packets()[i].packet, program.packets[i].packet) << i;
    // Arrival relative to the first packet vs the schedule. Generous: this machine is shared.
    const auto offset = board.packets()[i].at - first;
    const auto want = std::chrono::milliseconds(program.packets[i].at_ms);
    EXPECT_LT(std::chrono::abs(offset - want), std::chrono::milliseconds(25)) << i;
  }
}

}  // namespace
}  // namespace seqc::player
