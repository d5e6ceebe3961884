// What the device commands (group, battery, servo, offset, bus-info, play) share: the
// --port/--timeout options, opening the controller, and one request at a time with its reply.
//
// Requests the controller answers (battery, positions, offsets, bus info, erase) wait for that
// reply. Requests it does not answer (moves, run, stop, speed, offsets adjust/write, ...) are
// followed by a confirmation: GetBatteryVoltage, sent at most twice. The controller answers in
// the order it receives, so its reply shows the command arrived before it and the link works;
// without one, "no reply" would be indistinguishable from "done". Group notifications that
// arrive meanwhile (started, stopped, finished) are kept for the command to report.
//
// Failures become a message for "seqc: error: " and an exit status: no reply or a hang-up ->
// DeviceFailure, Ctrl-C -> Interrupted. The session never sleeps or reads the wall clock; all
// waiting is the link's, on the injected clock.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "runtime/cli/context.hpp"
#include "runtime/cli/exit_codes.hpp"
#include "runtime/io/clock.hpp"
#include "runtime/protocol/lsc_messages.hpp"
#include "runtime/upload/controller_link.hpp"

namespace seqc::cli {

// The options every device command takes.
struct DeviceOptions {
  std::string port;  // empty: find the one connected controller
  std::string timeout = "1s";
  std::string robot;                          // --robot, when the command has no other use for it
  const CLI::Option* robot_option = nullptr;  // the command's own --robot, when it has one
  std::string command;                        // "group speed", "battery": for messages

  // The --robot profile given ("" if none): `lsc-6` selects that board's dialect.
  std::string profile() const;
};
void add_device_options(CLI::App& cmd, DeviceOptions& options);
// --robot PROFILE, for commands that accept servo names.
void add_robot_option(CLI::App& cmd, std::string& profile);
// The options of a command that acts on several servos: SERVO... (ids, or names with --robot),
// --robot and the device options.
struct ServoListOptions {
  DeviceOptions device;
  std::vector<std::string> servos;
  std::string robot;
};
// Adds them in that order, SERVO required.
void add_servo_list_options(CLI::App& cmd, ServoListOptions& options);
// Prints "seqc: error: MESSAGE" and returns ExitCode::Usage.
ExitCode usage_error(Context& ctx, const std::string& message);

struct DeviceError {
  ExitCode code = ExitCode::DeviceFailure;
  std::string message;
};

class ControllerSession final : private upload::LinkObserver {
 public:
  // `port_name` is what messages call the device ("emu:xarm", "/dev/ttyUSB0 at 9600 baud").
  // Becomes the link's observer, to keep the notifications it skips.
  ControllerSession(upload::ControllerLink& link, io::Duration timeout, std::string port_name);
  ~ControllerSession() override;
  ControllerSession(const ControllerSession&) = delete;
  ControllerSession& operator=(const ControllerSession&) = delete;

  // Sends `request` and returns the first reply of type R; nullopt on failure (see error()).
  // `what` names the awaited reply for the message, e.g. "the battery voltage".
  template <class R>
  std::optional<R> ask(const lsc::Request& request, const std::string& what) {
    auto reply = exchange(
        request, [](const lsc::Reply& r) { return std::holds_alternative<R>(r); }, what);
    if (!reply) return std::nullopt;
    return std::get<R>(*reply);
  }

  // Sends a request the controller does not answer and confirms it arrived (see above).
  bool tell(const lsc::Request& request);

  // Group notifications received so far, in order.
  const std::vector<lsc::Reply>& notifications() const { return notifications_; }
  const std::optional<DeviceError>& error() const { return error_; }
  upload::ControllerLink& link() { return link_; }
  io::Duration timeout() const { return timeout_; }
  const std::string& port_name() const { return port_name_; }

 private:
  void on_notification(const lsc::Reply& reply) override { notifications_.push_back(reply); }
  std::optional<lsc::Reply> exchange(const lsc::Request& request,
                                     const std::function<bool(const lsc::Reply&)>& want,
                                     const std::string& what);
  // Drains, sends, waits up to the timeout for a reply `want` takes.
  upload::WaitResult round_trip(const lsc::Request& request,
                                const std::function<bool(const lsc::Reply&)>& want);
  void fail_wait(const upload::WaitResult& result, const std::string& what);
  bool send(const lsc::Request& request);
  void fail(ExitCode code, std::string message);
  void drain();

  upload::ControllerLink& link_;
  io::Duration timeout_;
  std::string port_name_;
  std::vector<lsc::Reply> notifications_;
  std::optional<DeviceError> error_;
};

// Opens the controller `options` names, runs `body`, and prints a failure as
// "seqc: error: ..." on ctx.err. Returns body's status, or the failure's.
// The --timeout text is checked first (usage error).
using SessionBody = std::function<ExitCode(ControllerSession&)>;
ExitCode run_on_controller(Context& ctx, const DeviceOptions& options, const SessionBody& body);
// run_on_controller for one request the controller does not answer: tells it and, once it is
// confirmed, prints `done` on ctx.out.
ExitCode tell_on_controller(Context& ctx, const DeviceOptions& options, const lsc::Request& request,
                            const std::string& done);

// "1 s", "250 ms".
std::string describe_duration(io::Duration d);

}  // namespace seqc::cli
