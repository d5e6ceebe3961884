// seqc upload FILE [--port P] [--group N] [--run [--times K|--forever]] [--dry-run]
//                  [--trace FILE] [--strict] [--retries N]
// Compiles FILE, downloads it into an action group of the servo controller (runtime/upload)
// and, with --run, starts it. An invalid file sends nothing and opens no port.
#include <fstream>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "compiler/backend/servo_backend.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/compile_report.hpp"
#include "runtime/cli/group_dialect.hpp"
#include "runtime/cli/port_open.hpp"
#include "runtime/protocol/lsc_messages.hpp"
#include "runtime/upload/progress_text.hpp"
#include "runtime/upload/trace_transport.hpp"

namespace seqc::cli {
namespace {

struct UploadArgs {
  std::string file;
  std::string port;
  int group = 0;
  bool run = false;
  int times = 1;
  bool dry_run = false;
  std::string trace;
  bool forever = false;
  bool strict = false;
  int retries = 4;
};

ExitCode exit_code_for(upload::UploadStatus s) {
  switch (s) {
    case upload::UploadStatus::Completed:
      return ExitCode::Ok;
    case upload::UploadStatus::Interrupted:
      return ExitCode::Interrupted;
    case upload::UploadStatus::BadPlan:
      return ExitCode::Internal;
    default:
      return ExitCode::DeviceFailure;
  }
}

std::string plural(std::size_t n, const char* word) {
  return fmt::format("{} {}{}", n, word, n == 1 ? "" : "s");
}

ExitCode run_upload(Context& ctx, const UploadArgs& a) {
  Compiled c = compile_and_report(ctx, a.file, a.strict);
  if (c.code != ExitCode::Ok) return c.code;
  if (explain_no_storage(c.output, a.file, ctx.err)) return ExitCode::InvalidInput;
  const compiler::ServoProgram* program = c.output.servo_program();
  if (program == nullptr) {
    ctx.err << "seqc: error: " << a.file << ": not a servo controller program\n";
    return ExitCode::InvalidInput;
  }
  const auto group = static_cast<std::uint8_t>(a.group);
  auto planned = backend::plan_download(*program, group);
  if (!planned) {
    ctx.err << "seqc: error: " << a.file << ": " << planned.error().message << "\n";
    return ExitCode::InvalidInput;
  }
  const std::unique_ptr<GroupDialect> dialect = dialect_for(std::move(planned).value());
  const std::size_t actions = program->keyframes.size();

  if (a.dry_run) {
    ctx.out << dialect->session_hex(group, a.run,
                                    static_cast<std::uint16_t>(a.forever ? 0 : a.times));
    if (ctx.verbosity >= 0)
      ctx.err << "seqc: dry run: " << plural(actions, "action") << " for group " << a.group
              << "; nothing was sent\n";
    return ExitCode::Ok;
  }

  std::ofstream trace_file;
  if (!a.trace.empty()) {
    trace_file.open(a.trace, std::ios::out | std::ios::trunc);
    if (!trace_file) {
      ctx.err << "seqc: error: --trace " << a.trace << ": cannot write the file\n";
      return ExitCode::FileError;
    }
  }

  PortOpenResult opened = open_controller_port(a.port, ctx);
  if (!opened.port) {
    ctx.err << "seqc: error: " << opened.failure.message << "\n";
    return opened.failure.code;
  }
  OpenedPort& port = *opened.port;
  io::Clock& clock = *port.clock;
  std::unique_ptr<upload::TraceTransport> trace;
  io::Transport* transport = port.transport.get();
  if (trace_file.is_open()) {
    trace = std::make_unique<upload::TraceTransport>(*transport, clock, trace_file);
    transport = trace.get();
  }

  if (const std::string why = dialect->too_big_for(*transport); !why.empty()) {
    ctx.err << "seqc: error: " << a.file << ": " << why << "\n";
    return ExitCode::InvalidInput;
  }
  upload::UploadOptions options;
  options.group = group;
  options.retries = a.retries;
  options.run = a.run;
  options.run_times = static_cast<std::uint16_t>(a.forever ? 0 : a.times);
  upload::ProgressPrinter progress(ctx.err, ctx.err_is_terminal, ctx.verbosity,
                                   ctx.terminal_columns);
  if (ctx.verbosity > 0) {
    ctx.err << "upload: " << plural(actions, "action") << " into group " << a.group << " on "
            << transport->describe() << " (" << dialect->board() << " dialect)\n";
  }
  const upload::UploadResult r =
      dialect->upload(*transport, clock, ctx.interrupted, options, &progress);
  progress.finish();

  const double secs = std::chrono::duration<double>(r.elapsed).count();
  const std::string where = transport->describe() + (port.emulated() ? ", emulated time" : "");
  if (!r.ok()) {
    ctx.err << "seqc: error: " << r.message << "\n";
    ctx.err << "seqc: " << upload::describe_group_state(r.group_state, group) << "\n";
    if (r.erase_sent && r.erase_confirmed) {
      ctx.err << "seqc: sent GroupErase for group " << a.group
              << " and the controller confirmed it: step 5 was sent but never confirmed, so the "
                 "group is erased rather than left holding a partial download\n";
    } else if (r.erase_sent) {
      ctx.err << "seqc: sent GroupErase for group " << a.group
              << ", but the controller did not confirm it: the group may hold a partial "
                 "download; upload again\n";
    }
    if (r.stop_sent) ctx.err << "seqc: sent GroupStop: no group is playing\n";
    return exit_code_for(r.status);
  }
  std::string detail = fmt::format("{}, {:.1f} s", where, secs);
  if (r.retries > 0) detail += ", " + plural(static_cast<std::size_t>(r.retries), "re-send");
  if (r.restarts > 0) detail += ", " + plural(static_cast<std::size_t>(r.restarts), "restart");
  if (r.reopens > 0) {
    detail += ", the port came back " + plural(static_cast<std::size_t>(r.reopens), "time");
  }
  if (ctx.verbosity < 0) return ExitCode::Ok;  // --quiet: the exit status says it
  ctx.err << "seqc: the controller acknowledged " << plural(r.actions_acknowledged, "action")
          << " into group " << a.group << " (" << detail << ")\n";
  if (a.run) {
    const std::string times =
        a.forever ? "looping until stopped" : plural(static_cast<std::size_t>(a.times), "time");
    if (r.run_reported) {
      ctx.err << "seqc: group " << a.group << " started (" << times << ")\n";
    } else {
      ctx.err << "seqc: asked the controller to run group " << a.group << " (" << times << "); "
              << dialect->unconfirmed_run() << "\n";
    }
  }
  return ExitCode::Ok;
}

}  // namespace

void add_upload_command(CLI::App& app, Context& ctx, Outcome& result) {
  auto a = std::make_shared<UploadArgs>();
  CLI::App* cmd = app.add_subcommand(
      "upload", "Compile a file and store it in an action group of the servo controller");
  cmd->add_option("FILE", a->file, "Choreography file (.yaml)")->required();
  cmd->add_option("--port", a->port,
                  "Device: /dev/ttyUSB0[@BAUD], hid, emu:xarm[?FAULTS], emu:lsc6[?OPTIONS] "
                  "(default: the one controller found)");
  cmd->add_option("--group", a->group, "Action group to store it in (0-254, default 0)")
      ->check(CLI::Range(0, 254));
  CLI::Option* run = cmd->add_flag("--run", a->run, "Start the group once it is stored");
  CLI::Option* times =
      cmd->add_option("--times", a->times, "With --run: how many times to play it (1-65535)")
          ->check(CLI::Range(1, 65535))
          ->needs(run);
  cmd->add_flag("--forever", a->forever, "With --run: play it until stopped")
      ->needs(run)
      ->excludes(times);
  cmd->add_flag("--dry-run", a->dry_run, "Print the frames it would send; open no port");
  cmd->add_option("--trace", a->trace,
                  "Write every byte sent and received, with times, to this file (docs/trace.md)");
  cmd->add_flag("--strict", a->strict, "Treat warnings as errors");
  cmd->add_option("--retries", a->retries,
                  "Re-sends of one frame before giving up (0-20, default 4)")
      ->check(CLI::Range(0, 20));
  cmd->callback([&ctx, &result, a] { result.code = run_upload(ctx, *a); });
}

}  // namespace seqc::cli
