#include "runtime/cli/controller_session.hpp"

#include "runtime/cli/commands.hpp"

#include <ostream>
#include <utility>

#include "compiler/source/units.hpp"
#include "runtime/cli/device_args.hpp"
#include "runtime/cli/lsc6_commands.hpp"
#include "runtime/cli/port_open.hpp"

namespace seqc::cli {
namespace {

// How many times the confirmation is sent before a command counts as unanswered: a controller
// still busy with the command itself may drop the first one (docs/protocol/servo-controller.md).
constexpr int kConfirmAttempts = 2;

const char* kCheckHint = "check that the controller is powered and connected, and --port";

}  // namespace

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
                   "Robot profile; lsc-6 selects the LSC-6 board's own dialect");
  }
  cmd.add_option("--port", options.port, "Port, as for `seqc upload` (default: the connected one)");
  cmd.add_option("--timeout", options.timeout, "How long to wait for each reply")
      ->capture_default_str();
}

void add_robot_option(CLI::App& cmd, std::string& profile) {
  cmd.add_option("--robot", profile,
                 "Robot profile (xarm, bus, lsc-16, lsc-32, lsc-6): allows servo names; lsc-6 "
                 "selects the LSC-6 board's own dialect");
}

void add_servo_list_options(CLI::App& cmd, ServoListOptions& options) {
  cmd.add_option("SERVO", options.servos, "Servo ids (or names with --robot)")->required();
  add_robot_option(cmd, options.robot);
  add_device_options(cmd, options.device);
}

ExitCode usage_error(Context& ctx, const std::string& message) {
  ctx.err << "seqc: error: " << message << "\n";
  return ExitCode::Usage;
}

std::string describe_duration(io::Duration d) {
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(d).count();
  if (ms >= 1000) return compiler::format_seconds(static_cast<std::uint64_t>(ms));
  return std::to_string(ms) + " ms";
}

ControllerSession::ControllerSession(upload::ControllerLink& link, io::Duration timeout,
                                     std::string port_name)
    : link_(link), timeout_(timeout), port_name_(std::move(port_name)) {
  link_.set_observer(this);
}

ControllerSession::~ControllerSession() { link_.set_observer(nullptr); }

void ControllerSession::fail(ExitCode code, std::string message) {
  if (!error_) error_ = DeviceError{code, std::move(message)};
}

void ControllerSession::drain() {
  // Replies nobody waits for any more (a late answer) must not be taken for the answer to the
  // next request. Notifications are kept (on_notification) for the command to report.
  link_.drain([](const lsc::Reply&) {});
}

bool ControllerSession::send(const lsc::Request& request) {
  if (error_) return false;
  if (link_.interrupted()) {
    fail(ExitCode::Interrupted, "interrupted");
    return false;
  }
  auto sent = link_.send(request);
  if (!sent) {
    fail(ExitCode::DeviceFailure, "cannot send " + lsc::describe(request) + " to " + port_name_ +
                                      ": " + sent.error().message);
    return false;
  }
  return true;
}

upload::WaitResult ControllerSession::round_trip(
    const lsc::Request& request, const std::function<bool(const lsc::Reply&)>& want) {
  upload::WaitResult r;
  r.status = upload::WaitStatus::Error;
  drain();
  if (!send(request)) return r;
  const io::TimePoint deadline = link_.clock().now() + timeout_;
  return link_.wait_for(
      [&](const lsc::Reply& reply) {
        // Skipped notifications reach on_notification through the link.
        return want(reply) ? upload::Verdict::Take : upload::Verdict::Skip;
      },
      deadline);
}

void ControllerSession::fail_wait(const upload::WaitResult& r, const std::string& what) {
  switch (r.status) {
    case upload::WaitStatus::Matched:
      return;
    case upload::WaitStatus::Timeout:
      fail(ExitCode::DeviceFailure, "no reply from the controller on " + port_name_ + " within " +
                                        describe_duration(timeout_) + " (" + what + "); " +
                                        kCheckHint);
      return;
    case upload::WaitStatus::HangUp:
      fail(ExitCode::DeviceFailure,
           "the controller on " + port_name_ + " went away (" + r.message + ")");
      return;
    case upload::WaitStatus::Interrupted:
      fail(ExitCode::Interrupted, "interrupted while waiting for the controller's reply");
      return;
    case upload::WaitStatus::Error:
      // A send failure has already been recorded; this is a read failure.
      fail(ExitCode::DeviceFailure, "reading from " + port_name_ + " failed: " + r.message);
      return;
  }
}

std::optional<lsc::Reply> ControllerSession::exchange(
    const lsc::Request& request, const std::function<bool(const lsc::Reply&)>& want,
    const std::string& what) {
  if (error_) return std::nullopt;
  upload::WaitResult r = round_trip(request, want);
  if (r.ok()) return std::move(r.reply);
  fail_wait(r, "waiting for " + what);
  return std::nullopt;
}

bool ControllerSession::tell(const lsc::Request& request) {
  if (error_ || !send(request)) return false;
  const auto is_battery = [](const lsc::Reply& r) {
    return std::holds_alternative<lsc::BatteryVoltage>(r);
  };
  upload::WaitResult r;
  for (int attempt = 0; attempt < kConfirmAttempts && !error_; ++attempt) {
    r = round_trip(lsc::GetBatteryVoltage{}, is_battery);
    if (r.ok()) return true;
    if (r.status != upload::WaitStatus::Timeout) break;
  }
  if (r.status == upload::WaitStatus::Timeout && !error_) {
    fail(ExitCode::DeviceFailure,
         "no reply from the controller on " + port_name_ + ": " + lsc::describe(request) +
             " has no answer of its own, and the battery check sent after it went unanswered "
             "(sent " +
             std::to_string(kConfirmAttempts) + " times, " + describe_duration(timeout_) +
             " each), so it may not have arrived; " + kCheckHint);
  } else {
    fail_wait(r, "confirming " + lsc::describe(request));
  }
  return false;
}

ExitCode run_on_controller(Context& ctx, const DeviceOptions& options, const SessionBody& body) {
  // Everything that reaches here needs a command or an answer the LSC-6 firmware lacks.
  if (is_lsc6_board(options.profile(), options.port)) return refuse_on_lsc6(ctx, options.command);
  auto timeout = parse_timeout(options.timeout);
  if (!timeout) return usage_error(ctx, timeout.error().message);
  PortOpenResult opened = open_controller_port(options.port, ctx);
  if (!opened.port) {
    ctx.err << "seqc: error: " << opened.failure.message << "\n";
    return opened.failure.code;
  }
  OpenedPort& port = *opened.port;
  upload::ControllerLink link(*port.transport, *port.clock, ctx.interrupted);
  ControllerSession session(link, *timeout, port.transport->describe());
  const ExitCode code = body(session);
  if (session.error()) {
    ctx.err << "seqc: error: " << session.error()->message << "\n";
    return session.error()->code;
  }
  return code;
}

ExitCode tell_on_controller(Context& ctx, const DeviceOptions& options, const lsc::Request& request,
                            const std::string& done) {
  return run_on_controller(ctx, options, [&](ControllerSession& s) {
    if (!s.tell(request)) return ExitCode::DeviceFailure;
    // `done` ends with a newline, as the callers write it.
    summarize(ctx, done.substr(0, done.size() - (done.ends_with('\n') ? 1 : 0)));
    return ExitCode::Ok;
  });
}

}  // namespace seqc::cli
