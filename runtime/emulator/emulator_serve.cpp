// `seqc emulate`'s servers (emulator_serve.hpp): one function per emulator, each making its
// device, serving it on a pseudo-terminal until the stop flag, and gathering what it received.
#include "runtime/emulator/emulator_serve.hpp"

#include <algorithm>
#include <chrono>
#include <optional>
#include <utility>

#include "protocol/raspblock/raspblock.hpp"
#include "runtime/emulator/group_dump.hpp"
#include "runtime/emulator/lsc6_emulator.hpp"
#include "runtime/emulator/pty_device.hpp"
#include "runtime/emulator/pty_server.hpp"
#include "runtime/emulator/raspblock_emulator.hpp"
#include "runtime/emulator/received_record.hpp"
#include "runtime/emulator/xarm_config.hpp"
#include "runtime/emulator/xarm_emulator.hpp"

namespace seqc::emu {
namespace {

// The servo controller's UART rate (docs/protocol/servo-controller.md, Framing).
constexpr std::uint32_t kXArmBaud = 9600;

std::string baud_text(std::uint32_t baud) {
  return baud ? std::to_string(baud) + " baud" : std::string("unpaced");
}

std::string frames_text(std::size_t frames, std::size_t bytes) {
  return std::to_string(frames) + " frames, " + std::to_string(bytes) + " bytes";
}

// Opens the terminal; on failure fills `result` (NoTerminal) and returns nullopt.
std::optional<PtyServer> open_terminal(const PtyOptions& options, ServeResult& result) {
  auto opened = PtyServer::open(options);
  if (!opened) {
    result.status = ServeStatus::NoTerminal;
    result.detail = opened.error().message;
    return std::nullopt;
  }
  return std::move(*opened);
}

}  // namespace

ServeResult serve_xarm(const ServeOptions& options, io::Clock& clock, const std::atomic<bool>& stop,
                       ServeEvents& events) {
  ServeResult result;
  result.device = "an xArm controller";
  XArmConfig config;
  config.baud = options.baud.value_or(kXArmBaud);
  // The fault items, and the flash's size (groups=N, flash=N), as `emu:xarm?...` takes them.
  if (Status applied = apply_emulator_options(options.faults, config); !applied) {
    result.status = ServeStatus::BadFaults;
    result.detail = applied.error().message;
    return result;
  }
  if (options.seed) config.faults.seed = *options.seed;
  auto positions = parse_positions(options.positions);
  if (!positions) {
    result.status = ServeStatus::BadPositions;
    result.detail = positions.error().message;
    return result;
  }
  config.initial_positions = *positions;
  for (const auto& [id, position] : *positions) {
    config.servo_count = std::max<std::size_t>(config.servo_count, id);
  }

  PtyOptions pty_options;
  pty_options.baud = config.baud;
  if (options.link) pty_options.link = *options.link;
  std::optional<PtyServer> server = open_terminal(pty_options, result);
  if (!server) return result;

  XArmEmulator emu(config);
  ControllerPtyDevice device(emu);
  events.serving(
      server->slave_path(), result.device,
      " (" + baud_text(config.baud) + ", faults: " + describe_faults(config.faults) + ")");
  auto stopped = server->serve(device, clock, stop);
  // A hang-up with back-after: the device comes back on a new terminal (--link follows it).
  while (stopped && *stopped == PtyServer::Stopped::HangUp && config.faults.back_after) {
    events.hung_up(emu.frames_received(), *config.faults.back_after);
    const io::TimePoint back = clock.now() + *config.faults.back_after;
    while (!stop.load() && clock.now() < back) {
      clock.sleep_until(std::min(back, clock.now() + std::chrono::milliseconds(50)));
    }
    if (stop.load()) break;
    const io::TimePoint resume = emu.now() + *config.faults.back_after;
    server.reset();
    auto opened = PtyServer::open(pty_options);
    if (!opened || !device.reconnect(resume)) {
      result.status = ServeStatus::NotBack;
      if (!opened) result.detail = opened.error().message;
      return result;
    }
    server.emplace(std::move(*opened));
    events.back(server->slave_path());
    stopped = server->serve(device, clock, stop, resume - io::TimePoint{0});
  }
  if (!stopped) {
    result.status = ServeStatus::Failed;
    result.detail = stopped.error().message;
  } else if (*stopped == PtyServer::Stopped::HangUp) {
    result.status = ServeStatus::HungUp;
    result.hung_up_at_frame = emu.frames_received();
  }
  result.received = frames_text(emu.frames_received(), emu.received_bytes().size());
  if (options.record) result.record = xarm_record_csv(emu);
  if (options.dump_groups) result.groups = dump_groups(emu);
  return result;
}

ServeResult serve_lsc6(const ServeOptions& options, io::Clock& clock, const std::atomic<bool>& stop,
                       ServeEvents& events) {
  ServeResult result;
  result.device = "an LSC-6 board";
  Lsc6Config config;
  if (auto ok = apply_lsc6_options(options.faults, config); !ok) {
    result.status = ServeStatus::BadFaults;
    result.detail = ok.error().message;
    return result;
  }
  if (options.baud) config.baud = *options.baud;
  if (options.seed) config.seed = *options.seed;

  PtyOptions pty_options;
  pty_options.baud = config.baud;
  if (options.link) pty_options.link = *options.link;
  std::optional<PtyServer> server = open_terminal(pty_options, result);
  if (!server) return result;
  events.serving(server->slave_path(), result.device,
                 " (" + baud_text(config.baud) + (config.run_reply ? "" : ", no answer to Run") +
                     (config.finish_notice ? "" : ", no end-of-run notice") +
                     (config.drop > 0 ? ", drop " + std::to_string(config.drop) : std::string()) +
                     ")");

  Lsc6Emulator board(config);
  ControllerPtyDevice device(board);
  auto stopped = server->serve(device, clock, stop);
  if (!stopped) {
    result.status = ServeStatus::Failed;
    result.detail = stopped.error().message;
  }
  result.received = frames_text(board.received().size(), board.received_bytes().size());
  if (options.record) result.record = lsc6_record_csv(board);
  if (options.dump_groups) result.groups = dump_groups(board);
  return result;
}

ServeResult serve_raspblock(const ServeOptions& options, io::Clock& clock,
                            const std::atomic<bool>& stop, ServeEvents& events) {
  ServeResult result;
  result.device = "a Raspblock board";
  PtyOptions pty_options;
  pty_options.baud = options.baud.value_or(raspblock::kBaud);
  if (options.link) pty_options.link = *options.link;
  std::optional<PtyServer> server = open_terminal(pty_options, result);
  if (!server) return result;

  RaspblockEmulator board;
  RaspblockPtyDevice device(board, events.log());
  events.serving(server->slave_path(), result.device, "; state changes follow");
  auto stopped = server->serve(device, clock, stop);
  if (!stopped) {
    result.status = ServeStatus::Failed;
    result.detail = stopped.error().message;
  } else if (*stopped == PtyServer::Stopped::HangUp) {
    result.status = ServeStatus::HungUp;
  }
  result.received = std::to_string(board.packets().size()) + " packets, " +
                    std::to_string(board.rejections().size()) + " rejected (" +
                    std::to_string(board.bad_checksums()) + " bad checksums)";
  if (options.record) result.record = timeline_csv(board.timeline());
  return result;
}

std::string faults_help() {
  std::string out = "Faults, KEY=VALUE,... e.g. drop=0.01,late=0.02,late-by=400ms\nxarm:";
  for (const FaultKey& k : fault_keys()) {
    const char* value = k.value == FaultValue::Rate         ? "=P"
                        : k.value == FaultValue::Duration   ? "=TIME"
                        : k.value == FaultValue::ClockError ? "=ERR"
                                                            : "=N";
    out += "\n  " + std::string(k.key) + value + ": " + std::string(k.does);
  }
  out += "\nlsc6:";
  for (const Lsc6OptionKey& k : lsc6_option_keys()) {
    if (!k.fault) continue;
    out += "\n  " + std::string(k.key) + (k.value.empty() ? "" : "=") + std::string(k.value) +
           ": " + std::string(k.does);
  }
  return out +
         "\n(P: a rate 0..1 per frame; TIME: ms, s, us or ns; ERR: a percent or ppm, e.g. "
         "+0.8%, -1%, +120ppm)";
}

}  // namespace seqc::emu
