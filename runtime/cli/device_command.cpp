#include "runtime/cli/device_command.hpp"

#include <ostream>
#include <utility>

#include "runtime/boards/board.hpp"
#include "runtime/boards/board_link.hpp"
#include "runtime/boards/servo_args.hpp"
#include "runtime/cli/board_text.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/device_args.hpp"
#include "runtime/cli/trace_option.hpp"

namespace seqc::cli {

std::string DeviceOptions::profile() const {
  if (robot_option != nullptr) {
    return robot_option->count() > 0 ? robot_option->as<std::string>() : std::string();
  }
  return robot;
}

void add_device_options(CLI::App& cmd, DeviceOptions& options) {
  const CLI::App* parent = cmd.get_parent();
  options.command = parent != nullptr && parent->get_parent() != nullptr
                        ? parent->get_name() + " " + cmd.get_name()
                        : cmd.get_name();
  options.robot_option = cmd.get_option_no_throw("--robot");
  if (options.robot_option == nullptr) {
    cmd.add_option("--robot", options.robot,
                   "Robot profile; lsc-6 and learm select the LSC-6 board's own dialect");
  }
  cmd.add_option("--port", options.port, "Port, as for `seqc upload` (default: the connected one)");
  cmd.add_option("--timeout", options.timeout, "How long to wait for each reply")
      ->capture_default_str();
  add_trace_option(cmd, options.trace);
}

void add_robot_option(CLI::App& cmd, std::string& profile) {
  cmd.add_option(
      "--robot", profile,
      "Robot profile (xarm, bus, lsc-16, lsc-32, lsc-6, learm): allows servo names; lsc-6 "
      "and learm select the LSC-6 board's own dialect");
}

void add_servo_list_options(CLI::App& cmd, ServoListOptions& options) {
  cmd.add_option("SERVO", options.servos, "Servo ids (or names with --robot)")->required();
  add_robot_option(cmd, options.robot);
  add_device_options(cmd, options.device);
}

ExitCode run_on_controller(Context& ctx, const DeviceOptions& options, const SessionBody& body) {
  // Everything that reaches here asks something only a board with queries answers.
  const boards::Board& board = boards::board_for_command(options.profile(), options.port);
  if (!board.queries) return refuse_command(ctx, board, options.command);
  return run_on_board(ctx, options, board, [&](const boards::Line& line, const std::string& port) {
    upload::ControllerLink link(line.transport, line.clock, ctx.interrupted);
    boards::XarmSession session(link, line.timeout);
    const ExitCode code = body(session);
    if (session.failure()) return report_outcome(ctx, *session.failure(), line, port, board);
    return code;
  });
}

ExitCode run_on_board(Context& ctx, const DeviceOptions& options, const boards::Board& board,
                      const LineBody& body) {
  auto timeout = boards::parse_timeout(options.timeout);
  if (!timeout) return usage_error(ctx, timeout.error().message);
  stop_cleanly_from_now(ctx);
  boards::TraceFile trace;
  if (const ExitCode c = open_trace(ctx, trace, options.trace); c != ExitCode::Ok) return c;
  const boards::BoardLink link = boards::open_link({options.port, &board}, trace, ctx.clock,
                                                   ctx.hooks, ctx.interrupted, *timeout);
  if (!link.port) return say_port_failure(ctx, link, "");
  return body(*link.line, link.transport->describe());
}

ExitCode report_outcome(Context& ctx, const boards::Outcome& outcome, const boards::Line& line,
                        const std::string& port, const boards::Board& board) {
  const BoardError e = outcome_text(outcome, port, line.timeout, board.called);
  return fail(ctx, e.code, e.message);
}

ExitCode print_servo_readings(Context& ctx, const boards::ServoReadings& readings,
                              const std::optional<compiler::RobotInfo>& robot) {
  ctx.out << readings.table;
  if (readings.missing.empty()) return ExitCode::Ok;
  ctx.err << "seqc: error: the controller reported no " << readings.column << " for "
          << servo_labels(readings.missing, robot) << " (not on the bus, or not answering)\n";
  return ExitCode::DeviceFailure;
}

ExitCode tell_on_controller(Context& ctx, const DeviceOptions& options, const lsc::Request& request,
                            const std::string& done) {
  return run_on_controller(ctx, options, [&](boards::XarmSession& s) {
    if (!s.tell(request)) return ExitCode::DeviceFailure;
    // `done` ends with a newline, as the callers write it.
    summarize(ctx, done.substr(0, done.size() - (done.ends_with('\n') ? 1 : 0)));
    return ExitCode::Ok;
  });
}

}  // namespace seqc::cli
