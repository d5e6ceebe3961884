#include "runtime/cli/emulate_lsc6.hpp"

#include <atomic>
#include <ostream>

#include "runtime/emulator/group_dump.hpp"
#include "runtime/emulator/lsc6_emulator.hpp"
#include "runtime/emulator/pty_device.hpp"
#include "runtime/emulator/pty_server.hpp"
#include "runtime/io/disk.hpp"
#include "runtime/protocol/lsc6_messages.hpp"

namespace seqc::cli {
namespace {

std::string seconds(io::TimePoint at) {
  const auto us = std::chrono::duration_cast<std::chrono::microseconds>(at).count();
  std::string frac = std::to_string(us % 1000000);
  return std::to_string(us / 1000000) + "." + std::string(6 - frac.size(), '0') + frac;
}

// One CSV line per frame the receiver completed (the same columns as the xarm record).
std::string lsc6_record(const emu::Lsc6Emulator& emu) {
  std::string out = "time_s,status,bytes,message\n";
  for (const auto& r : emu.received()) {
    const char* status = r.dropped_fault ? "fault" : r.dropped_busy ? "busy" : "ok";
    std::string message;
    if (auto frame = lsc::decode_serial(r.raw)) {
      auto request = lsc6::decode_request(*frame);
      message = request ? lsc6::describe(*request) : "ignored: " + request.error().message;
    }
    if (message.find_first_of(",\"") != std::string::npos) {
      std::string quoted = "\"";
      for (char c : message) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
      message = quoted + "\"";
    }
    out += seconds(r.at) + "," + status + "," + to_hex(r.raw) + "," + message + "\n";
  }
  return out;
}

}  // namespace

ExitCode run_emulate_lsc6(const Lsc6EmulateArgs& args, Context& ctx) {
  emu::Lsc6Config config;
  if (auto ok = emu::apply_lsc6_options(args.options, config); !ok) {
    ctx.err << "seqc: error: --faults: " << ok.error().message << "\n";
    return ExitCode::Usage;
  }
  if (args.baud) config.baud = *args.baud;
  if (args.seed) config.seed = *args.seed;

  emu::PtyOptions pty_options;
  pty_options.baud = config.baud;
  if (args.link) pty_options.link = *args.link;
  auto server = emu::PtyServer::open(pty_options);
  if (!server) {
    ctx.err << "seqc: error: cannot create a pseudo-terminal: " << server.error().message << "\n";
    return ExitCode::PortUnavailable;
  }
  ctx.out << server->slave_path() << "\n" << std::flush;
  ctx.err << "seqc: emulating an LSC-6 board on " << server->slave_path() << " ("
          << (config.baud ? std::to_string(config.baud) + " baud" : std::string("unpaced"))
          << (config.run_reply ? "" : ", no answer to Run")
          << (config.finish_notice ? "" : ", no end-of-run notice")
          << (config.drop > 0 ? ", drop " + std::to_string(config.drop) : std::string())
          << "); Ctrl-C to stop\n";
  ctx.err.flush();

  std::atomic<bool> never{false};
  const std::atomic<bool>& stop = ctx.interrupted ? *ctx.interrupted : never;
  emu::Lsc6Emulator board(config);
  emu::ControllerPtyDevice device(board);
  auto stopped = server->serve(device, ctx.clock, stop);
  ExitCode code = ExitCode::Ok;
  if (!stopped) {
    ctx.err << "seqc: error: " << stopped.error().message << "\n";
    code = ExitCode::DeviceFailure;
  }
  ctx.err << "seqc: received " << board.received().size() << " frames, "
          << board.received_bytes().size() << " bytes\n";
  if (args.record) {
    if (auto ok = io::write_file_atomically(*args.record, lsc6_record(board)); !ok) {
      ctx.err << "seqc: error: --record " << *args.record << ": " << ok.error().message << "\n";
      return ExitCode::FileError;
    }
  }
  if (args.dump_groups) {
    if (auto ok = io::write_file_atomically(*args.dump_groups, emu::dump_groups(board)); !ok) {
      ctx.err << "seqc: error: --dump-groups " << *args.dump_groups << ": " << ok.error().message
              << "\n";
      return ExitCode::FileError;
    }
  }
  return code;
}

}  // namespace seqc::cli
