// `seqc emulate xarm|lsc6|raspblock`: serves a device emulator on a pseudo-terminal (the
// board's server, runtime/emulator/emulator_serve.hpp). The slave's path is the one line on
// stdout; progress and the Raspblock's state changes go to stderr. On exit, --record writes what
// was received and --dump-groups the stored groups of a board that stores them.
#include <atomic>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "runtime/boards/board.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/emulator/emulator_serve.hpp"
#include "runtime/io/disk.hpp"

namespace seqc::cli {
namespace {

struct EmulateOptions {
  std::string device;
  std::uint32_t baud = 0;
  std::string faults;
  std::uint64_t seed = 1;
  std::string link;
  std::string record;
  std::string dump_groups;
  std::string positions;
  const CLI::App* cmd = nullptr;  // the subcommand, which knows the options given

  bool given(const char* option) const { return cmd->count(option) > 0; }
};

// What the server reports while it runs, said on the command's streams.
class Events final : public emu::ServeEvents {
 public:
  explicit Events(Context& ctx) : ctx_(ctx) {}
  void serving(const std::string& path, const std::string& device,
               const std::string& settings) override {
    ctx_.out << path << "\n" << std::flush;
    ctx_.err << "seqc: emulating " << device << " on " << path << settings << "; Ctrl-C to stop\n";
    ctx_.err.flush();
  }
  void hung_up(std::size_t frame, io::Duration back_in) override {
    ctx_.err << "seqc: emulated hang-up at frame " << frame << " (--faults hangup-at); back in "
             << std::chrono::duration<double>(back_in).count() << " s\n";
    ctx_.err.flush();
  }
  void back(const std::string& path) override {
    ctx_.out << path << "\n" << std::flush;
    ctx_.err << "seqc: the device is back on " << path << "\n";
    ctx_.err.flush();
  }
  std::ostream* log() override { return &ctx_.err; }

 private:
  Context& ctx_;
};

// Why `board`'s emulator refuses one of the options given (boards::refused_emulator_option);
// an empty string when it takes them all.
std::string refused_option(const EmulateOptions& o, const boards::Board& board) {
  unsigned given = 0;
  if (o.given("--faults")) given |= boards::kFaults;
  if (o.given("--seed")) given |= boards::kSeed;
  if (o.given("--dump-groups")) given |= boards::kDumpGroups;
  if (!o.positions.empty()) given |= boards::kPositions;
  const boards::RefusedOption r = boards::refused_emulator_option(board, given);
  const std::string why = r.reason.empty() ? "" : " (" + std::string(r.reason) + ")";
  switch (r.option) {
    case 0:
      return "";
    case boards::kFaults:
    case boards::kSeed:
      return "--faults and --seed apply to the xarm emulator only" + why;
    case boards::kDumpGroups:
      return "--dump-groups applies to the xarm emulator only" + why;
    default:
      return "--positions applies to the xarm emulator only" + why;
  }
}

ExitCode write_output(Context& ctx, const char* option, const std::string& path,
                      const std::string& text) {
  if (auto ok = io::write_file_safely(path, text); !ok) {
    return fail(ctx, ExitCode::FileError, std::string(option) + " " + ok.error().message);
  }
  return ExitCode::Ok;
}

ExitCode run_emulate(const EmulateOptions& o, Context& ctx) {
  const boards::Board* board = boards::board_for_emulator(o.device);
  if (board == nullptr || board->serve == nullptr) {
    return fail(ctx, ExitCode::Internal, "internal: no emulator " + o.device);
  }
  if (const std::string why = refused_option(o, *board); !why.empty()) return usage_error(ctx, why);
  emu::ServeOptions options;
  if (o.given("--baud")) options.baud = o.baud;
  options.faults = o.faults;
  if (o.given("--seed")) options.seed = o.seed;
  options.positions = o.positions;
  if (o.given("--link")) options.link = o.link;
  options.record = o.given("--record");
  options.dump_groups = o.given("--dump-groups");

  std::atomic<bool> never{false};
  const std::atomic<bool>& stop = ctx.interrupted ? *ctx.interrupted : never;
  Events events(ctx);
  stop_cleanly_from_now(ctx);
  const emu::ServeResult r = board->serve(options, ctx.clock, stop, events);
  ExitCode code = ExitCode::Ok;
  switch (r.status) {
    case emu::ServeStatus::Stopped:
      break;
    case emu::ServeStatus::BadFaults:
      return usage_error(ctx, "--faults: " + r.detail);
    case emu::ServeStatus::BadPositions:
      return usage_error(ctx, "--positions: " + r.detail);
    case emu::ServeStatus::NoTerminal:
      return fail(ctx, ExitCode::PortUnavailable, "cannot create a pseudo-terminal: " + r.detail);
    case emu::ServeStatus::NotBack:
      return fail(ctx, ExitCode::PortUnavailable,
                  "cannot serve the device again" + (r.detail.empty() ? "" : ": " + r.detail));
    case emu::ServeStatus::Failed:
      code = fail(ctx, ExitCode::DeviceFailure, r.detail);
      break;
    case emu::ServeStatus::HungUp:
      ctx.err << "seqc: emulated hang-up at frame " << r.hung_up_at_frame
              << " (--faults hangup-at)\n";
      break;
  }
  ctx.err << "seqc: received " << r.received << "\n";
  if (options.record) {
    if (ExitCode c = write_output(ctx, "--record", o.record, r.record); c != ExitCode::Ok) return c;
  }
  if (options.dump_groups) {
    if (ExitCode c = write_output(ctx, "--dump-groups", o.dump_groups, r.groups);
        c != ExitCode::Ok) {
      return c;
    }
  }
  return code;
}

// What `seqc emulate` serves (boards::served_emulators), as CLI11 checks it.
std::vector<std::string> served_devices() {
  const std::vector<std::string_view> names = boards::served_emulators();
  return {names.begin(), names.end()};
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
      ->check(CLI::IsMember(served_devices()));
  opts->cmd = cmd;
  cmd->add_option("--baud", opts->baud,
                  "xarm, lsc6: line rate both ways (10 bits per byte), 0 = unpaced\n(default "
                  "9600)");
  cmd->add_option("--faults", opts->faults, emu::faults_help());
  cmd->add_option("--seed", opts->seed, "Seed for the faults (default 1)");
  cmd->add_option("--link", opts->link, "Also create this symlink to the terminal");
  cmd->add_option(
      "--record", opts->record,
      "On exit, write what was received as CSV\n(xarm: every frame; raspblock: state timeline)");
  cmd->add_option("--dump-groups", opts->dump_groups,
                  "xarm, lsc6: on exit, write every valid stored group, one action\n"
                  "per line: GROUP INDEX TIME_MS ID=POSITION ...");
  cmd->add_option("--positions", opts->positions,
                  "xarm: servo positions at power-on, ID=POSITION,... e.g. 1=300,2=650\n"
                  "(as if posed by hand; for seqc teach and servo read)");
  cmd->callback([opts, &ctx, &result] { result.code = run_emulate(*opts, ctx); });
}

}  // namespace seqc::cli
