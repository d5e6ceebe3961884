// What the device commands (group, battery, servo, offset, bus-info, teach) share: the
// --port/--timeout/--robot options, opening the board's port, and the words for how it went.
//
// The exchange itself is boards::XarmSession (runtime/boards/xarm_session.hpp): requests the
// controller answers wait for that reply; requests it does not answer are followed by a
// GetBatteryVoltage confirmation, sent at most twice; group notifications that arrive meanwhile
// are kept. This file adds the words: the session's first failure becomes a message for
// "seqc: error: " and an exit status (board_text.hpp: no reply or a hang-up -> DeviceFailure,
// Ctrl-C -> Interrupted). Which board a command reaches is boards::board_for_command's choice.
// Nothing here sleeps or reads the wall clock; all waiting is the link's, on the injected clock.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "protocol/lsc/lsc_messages.hpp"
#include "runtime/boards/reading_table.hpp"
#include "runtime/boards/xarm_session.hpp"
#include "runtime/cli/context.hpp"
#include "runtime/cli/exit_codes.hpp"
#include "runtime/io/clock.hpp"
#include "runtime/upload/controller_link.hpp"

namespace seqc::cli {

// The options every device command takes.
struct DeviceOptions {
  std::string port;  // empty: find the one connected controller
  std::string timeout = "1s";
  std::string robot;                          // --robot, when the command has no other use for it
  const CLI::Option* robot_option = nullptr;  // the command's own --robot, when it has one
  std::string command;                        // "group speed", "battery": for messages
  std::string trace;                          // --trace FILE ("" = none)

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

// Opens the controller `options` names, runs `body` on a session with it, and prints the
// session's first failure as "seqc: error: ..." on ctx.err. Returns body's status, or the
// failure's. The --timeout text is checked first (usage error); a board without queries is
// refused (refuse_command).
using SessionBody = std::function<ExitCode(boards::XarmSession&)>;
ExitCode run_on_controller(Context& ctx, const DeviceOptions& options, const SessionBody& body);
// Opens the port `options` names for `board` and runs `body` with the line to it and the port's
// description for messages. The --timeout text is checked first (usage error); a port that does
// not open is said on ctx.err. With --trace the line's transport writes every byte to that file
// (trace_option.hpp), which is opened first. Returns body's status, or the failure's.
using LineBody = std::function<ExitCode(const boards::Line& line, const std::string& port)>;
ExitCode run_on_board(Context& ctx, const DeviceOptions& options, const boards::Board& board,
                      const LineBody& body);
// Says `outcome`'s failure on ctx.err, naming the far end as `board` calls it; returns its status.
ExitCode report_outcome(Context& ctx, const boards::Outcome& outcome, const boards::Line& line,
                        const std::string& port, const boards::Board& board);

// Prints `readings`' table on ctx.out; servos without a reading give "seqc: error: the controller
// reported no COLUMN for ..." and DeviceFailure.
ExitCode print_servo_readings(Context& ctx, const boards::ServoReadings& readings,
                              const std::optional<compiler::RobotInfo>& robot);

// run_on_controller for one request the controller does not answer: tells it and, once it is
// confirmed, says `done` (summarize).
ExitCode tell_on_controller(Context& ctx, const DeviceOptions& options, const lsc::Request& request,
                            const std::string& done);

}  // namespace seqc::cli
