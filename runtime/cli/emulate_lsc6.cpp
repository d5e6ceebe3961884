#include "runtime/cli/emulate_lsc6.hpp"

#include <atomic>
#include <ostream>

#include "runtime/emulator/group_dump.hpp"
#include "runtime/emulator/lsc6_emulator.hpp"
#include "runtime/emulator/pty_device.hpp"
#include "runtime/emulator/pty_server.hpp"
#include "runtime/emulator/received_record.hpp"
#include "runtime/io/disk.hpp"
#include "runtime/protocol/lsc6_messages.hpp"

namespace seqc::cli {
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
    if (auto ok = io::write_file_atomically(*args.record, emu::lsc6_record_csv(board)); !ok) {
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
