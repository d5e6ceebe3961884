// `seqc emulate xarm|lsc6|raspblock`: serves a device emulator on a pseudo-terminal. The slave's
// path is the one line on stdout; progress and the Raspblock's state changes go to stderr.
// On exit, --record writes what was received and --dump-groups (xarm, lsc6) the stored groups.
// The LSC-6 board is served by emulate_lsc6.cpp.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <ostream>
#include <string>

#include <CLI/CLI.hpp>

#include "runtime/cli/commands.hpp"
#include "runtime/cli/emulate_lsc6.hpp"
#include "runtime/emulator/group_dump.hpp"
#include "runtime/emulator/pty_server.hpp"
#include "runtime/emulator/raspblock_emulator.hpp"
#include "runtime/emulator/received_record.hpp"
#include "runtime/emulator/xarm_emulator.hpp"
#include "runtime/io/disk.hpp"
#include "runtime/protocol/lsc_messages.hpp"
#include "runtime/protocol/raspblock.hpp"

namespace seqc::cli {
namespace {

// The servo controller's UART rate (docs/protocol/servo-controller.md, Framing).
constexpr std::uint32_t kXArmBaud = 9600;

struct EmulateOptions {
  std::string device;
  std::uint32_t baud = 0;
  std::string faults;
  std::uint64_t seed = 1;
  std::string link;
  std::string record;
  std::string dump_groups;
  std::string positions;
  CLI::Option* baud_opt = nullptr;
  CLI::Option* faults_opt = nullptr;
  CLI::Option* seed_opt = nullptr;
  CLI::Option* link_opt = nullptr;
  CLI::Option* record_opt = nullptr;
  CLI::Option* dump_groups_opt = nullptr;
};

ExitCode run_emulate(const EmulateOptions& o, Context& ctx) {
  if (o.device == "lsc6") {
    if (!o.positions.empty()) {
      ctx.err << "seqc: error: --positions applies to the xarm emulator only\n";
      return ExitCode::Usage;
    }
    Lsc6EmulateArgs args;
    if (o.baud_opt->count() > 0) args.baud = o.baud;
    args.options = o.faults;
    if (o.seed_opt->count() > 0) args.seed = o.seed;
    if (o.link_opt->count() > 0) args.link = o.link;
    if (o.record_opt->count() > 0) args.record = o.record;
    if (o.dump_groups_opt->count() > 0) args.dump_groups = o.dump_groups;
    return run_emulate_lsc6(args, ctx);
  }
  const bool xarm = o.device == "xarm";
  if (!xarm && (o.faults_opt->count() > 0 || o.seed_opt->count() > 0)) {
    ctx.err << "seqc: error: --faults and --seed apply to the xarm emulator only (the Raspblock "
               "board never replies)\n";
    return ExitCode::Usage;
  }
  if (!xarm && o.dump_groups_opt->count() > 0) {
    ctx.err << "seqc: error: --dump-groups applies to the xarm emulator only (the Raspblock "
               "board stores no groups)\n";
    return ExitCode::Usage;
  }
  emu::XArmConfig config;
  config.baud = o.baud_opt->count() > 0 ? o.baud : kXArmBaud;
  if (xarm) {
    auto faults = emu::parse_faults(o.faults);
    if (!faults) {
      ctx.err << "seqc: error: --faults: " << faults.error().message << "\n";
      return ExitCode::Usage;
    }
    config.faults = *faults;
    if (o.seed_opt->count() > 0) config.faults.seed = o.seed;
    auto positions = emu::parse_positions(o.positions);
    if (!positions) {
      ctx.err << "seqc: error: --positions: " << positions.error().message << "\n";
      return ExitCode::Usage;
    }
    config.initial_positions = *positions;
    for (const auto& [id, position] : *positions) {
      config.servo_count = std::max<std::size_t>(config.servo_count, id);
    }
  } else if (!o.positions.empty()) {
    ctx.err << "seqc: error: --positions applies to the xarm emulator only\n";
    return ExitCode::Usage;
  }

  emu::PtyOptions pty_options;
  pty_options.baud = xarm ? config.baud : (o.baud_opt->count() > 0 ? o.baud : raspblock::kBaud);
  if (o.link_opt->count() > 0) pty_options.link = o.link;
  std::optional<emu::PtyServer> server;
  if (auto opened = emu::PtyServer::open(pty_options); opened) {
    server.emplace(std::move(*opened));
  } else {
    ctx.err << "seqc: error: cannot create a pseudo-terminal: " << opened.error().message << "\n";
    return ExitCode::PortUnavailable;
  }
  ctx.out << server->slave_path() << "\n" << std::flush;

  std::atomic<bool> never{false};
  const std::atomic<bool>& stop = ctx.interrupted ? *ctx.interrupted : never;

  emu::XArmEmulator xarm_emu(config);
  emu::RaspblockEmulator rasp_emu;
  emu::ControllerPtyDevice xarm_dev(xarm_emu);
  emu::RaspblockPtyDevice rasp_dev(rasp_emu, &ctx.err);
  if (xarm) {
    ctx.err << "seqc: emulating an xArm controller on " << server->slave_path() << " ("
            << (config.baud ? std::to_string(config.baud) + " baud" : std::string("unpaced"))
            << ", faults: " << emu::describe_faults(config.faults) << "); Ctrl-C to stop\n";
  } else {
    ctx.err << "seqc: emulating a Raspblock board on " << server->slave_path()
            << "; state changes follow; Ctrl-C to stop\n";
  }
  ctx.err.flush();

  auto stopped =
      server->serve(xarm ? static_cast<emu::PtyDevice&>(xarm_dev) : rasp_dev, ctx.clock, stop);
  // A hang-up with back-after: the device comes back on a new terminal (--link follows it).
  while (xarm && stopped && *stopped == emu::PtyServer::Stopped::HangUp &&
         config.faults.back_after) {
    ctx.err << "seqc: emulated hang-up at frame " << xarm_emu.frames_received()
            << " (--faults hangup-at); back in "
            << std::chrono::duration<double>(*config.faults.back_after).count() << " s\n";
    ctx.err.flush();
    const io::TimePoint back = ctx.clock.now() + *config.faults.back_after;
    while (!stop.load() && ctx.clock.now() < back) {
      ctx.clock.sleep_until(std::min(back, ctx.clock.now() + std::chrono::milliseconds(50)));
    }
    if (stop.load()) break;
    const io::TimePoint resume = xarm_emu.now() + *config.faults.back_after;
    server.reset();
    auto opened = emu::PtyServer::open(pty_options);
    if (!opened || !xarm_dev.reconnect(resume)) {
      ctx.err << "seqc: error: cannot serve the device again"
              << (opened ? std::string() : ": " + opened.error().message) << "\n";
      return ExitCode::PortUnavailable;
    }
    server.emplace(std::move(*opened));
    ctx.out << server->slave_path() << "\n" << std::flush;
    ctx.err << "seqc: the device is back on " << server->slave_path() << "\n";
    ctx.err.flush();
    stopped = server->serve(xarm_dev, ctx.clock, stop, resume - io::TimePoint{0});
  }
  ExitCode code = ExitCode::Ok;
  if (!stopped) {
    ctx.err << "seqc: error: " << stopped.error().message << "\n";
    code = ExitCode::DeviceFailure;
  } else if (*stopped == emu::PtyServer::Stopped::HangUp) {
    ctx.err << "seqc: emulated hang-up at frame " << xarm_emu.frames_received()
            << " (--faults hangup-at)\n";
  }
  if (xarm) {
    ctx.err << "seqc: received " << xarm_emu.frames_received() << " frames, "
            << xarm_emu.received_bytes().size() << " bytes\n";
  } else {
    ctx.err << "seqc: received " << rasp_emu.packets().size() << " packets, "
            << rasp_emu.rejections().size() << " rejected (" << rasp_emu.bad_checksums()
            << " bad checksums)\n";
  }

  if (o.record_opt->count() > 0) {
    const std::string text =
        xarm ? emu::xarm_record_csv(xarm_emu) : emu::timeline_csv(rasp_emu.timeline());
    if (auto ok = io::write_file_atomically(o.record, text); !ok) {
      ctx.err << "seqc: error: --record " << o.record << ": " << ok.error().message << "\n";
      return ExitCode::FileError;
    }
  }
  if (o.dump_groups_opt->count() > 0) {
    if (auto ok = io::write_file_atomically(o.dump_groups, emu::dump_groups(xarm_emu)); !ok) {
      ctx.err << "seqc: error: --dump-groups " << o.dump_groups << ": " << ok.error().message
              << "\n";
      return ExitCode::FileError;
    }
  }
  return code;
}

}  // namespace

void add_emulate_command(CLI::App& app, Context& ctx, Outcome& result) {
  auto opts = std::make_shared<EmulateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "emulate",
      "Serve an emulated device on a pseudo-terminal until Ctrl-C (exit 0). Prints the\n"
      "terminal's path on stdout; point `seqc upload --port` (or any program) at it.");
  cmd->add_option("device", opts->device,
                  "xarm (servo controller), lsc6 (LSC-6 / LeArm board) or raspblock (car board)")
      ->required()
      ->check(CLI::IsMember({"xarm", "lsc6", "raspblock"}));
  opts->baud_opt =
      cmd->add_option("--baud", opts->baud,
                      "xarm, lsc6: line rate both ways (10 bits per byte), 0 = unpaced\n(default "
                      "9600)");
  opts->faults_opt =
      cmd->add_option("--faults", opts->faults,
                      "xarm faults KEY=VALUE,... e.g. drop=0.01,late=0.02,late-by=400ms\n"
                      "keys: drop, corrupt, late, dup, busy, reset (rates 0..1),\n"
                      "late-by, busy-for, boot-time, silent-after, hangup-at,\n"
                      "back-after (a hung-up device returns on a new terminal),\n"
                      "reset-at, seed\n"
                      "lsc6: drop, seed, no-run-reply, no-finish (firmware copies\n"
                      "that never answer Run or never announce the end of a run)");
  opts->seed_opt = cmd->add_option("--seed", opts->seed, "Seed for the faults (default 1)");
  opts->link_opt =
      cmd->add_option("--link", opts->link, "Also create this symlink to the terminal");
  opts->record_opt = cmd->add_option(
      "--record", opts->record,
      "On exit, write what was received as CSV\n(xarm: every frame; raspblock: state timeline)");
  opts->dump_groups_opt =
      cmd->add_option("--dump-groups", opts->dump_groups,
                      "xarm, lsc6: on exit, write every valid stored group, one action\n"
                      "per line: GROUP INDEX TIME_MS ID=POSITION ...");
  cmd->add_option("--positions", opts->positions,
                  "xarm: servo positions at power-on, ID=POSITION,... e.g. 1=300,2=650\n"
                  "(as if posed by hand; for seqc teach and servo read)");
  cmd->callback([opts, &ctx, &result] { result.code = run_emulate(*opts, ctx); });
}

}  // namespace seqc::cli
