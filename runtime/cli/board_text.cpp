#include "runtime/cli/board_text.hpp"

#include <ostream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "base/units.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/io/time_text.hpp"
#include "runtime/transport/port_spec.hpp"

namespace seqc::cli {
namespace {

// "emu:lsc6?seed=3" -> "emu:lsc6".
std::string without_options(const std::string& port) { return port.substr(0, port.find('?')); }

// "emu:xarm or emu:lsc6": the emulators of `board`'s family, as --port names them.
std::string emulator_ports(const boards::Board& board) {
  const std::vector<std::string_view> names = boards::family_emulators(board);
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const char* joint = i == 0 ? "" : i + 1 == names.size() ? " or " : ", ";
    out += joint + std::string("emu:") + std::string(names[i]);
  }
  return out;
}

}  // namespace

BoardError port_failure(const boards::PortFailure& f, const boards::PortRequest& request,
                        const std::string& subject) {
  const std::string& port = request.text;
  switch (f.problem) {
    case boards::PortProblem::Malformed:
      return {ExitCode::Usage, "--port: " + f.detail};
    case boards::PortProblem::EmulatorOptions: {
      auto spec = transport::parse_port(port);
      return {ExitCode::Usage,
              "--port " + (spec ? transport::format_port(*spec) : port) + ": " + f.detail};
    }
    case boards::PortProblem::WrongEmulator:
      if (request.board == nullptr || f.reached == nullptr) break;
      if (subject.empty()) {
        return {ExitCode::Usage,
                "--port " + without_options(port) + ": this command talks to the " +
                    std::string(request.board->family) + "; use " + emulator_ports(*request.board)};
      }
      return {ExitCode::Usage, "--port " + port + " is the " + std::string(f.reached->family) +
                                   "'s emulator; " + subject + " is for the " +
                                   std::string(request.board->key) + " (use --port " +
                                   emulator_ports(*request.board) + ")"};
    case boards::PortProblem::WrongKind:
      if (request.board == nullptr) break;
      return {ExitCode::Usage, "--port " + port + " is a USB HID device (the xArm's link); the " +
                                   std::string(request.board->name) +
                                   " board is reached over a serial port at " +
                                   std::to_string(request.board->baud) + " baud"};
    case boards::PortProblem::NeedsPort:
      if (request.board == nullptr) break;
      return {ExitCode::Usage,
              "name the board's serial port with --port, e.g. --port /dev/ttyAMA0 or --port "
              "ttyUSB0 (the board does not announce itself)\n  hint: --port " +
                  emulator_ports(*request.board) + " plays to the built-in board emulator"};
    case boards::PortProblem::NotFound:
    case boards::PortProblem::CannotOpen:
      return {ExitCode::PortUnavailable, f.detail};
  }
  return {ExitCode::Usage, "--port " + port + ": " + f.detail};
}

BoardError outcome_text(const boards::Outcome& o, const std::string& port, io::Duration timeout,
                        std::string_view called_view) {
  const std::string called(called_view);
  const std::string hint = "check that " + called + " is powered and connected, and --port";
  switch (o.failure) {
    case boards::Failure::None:
      break;
    case boards::Failure::SendFailed:
      return {ExitCode::DeviceFailure,
              "cannot send " + o.request + " to " + port + ": " + o.detail};
    case boards::Failure::NoReply:
      return {ExitCode::DeviceFailure, "no reply from " + called + " on " + port + " within " +
                                           io::duration_text(timeout) + " (waiting for " +
                                           o.awaiting + "); " + hint};
    case boards::Failure::Unconfirmed:
      return {ExitCode::DeviceFailure,
              "no reply from " + called + " on " + port + ": " + o.request +
                  " has no answer of its own, and the battery check sent after it went "
                  "unanswered (sent " +
                  std::to_string(o.attempts) + " times, " + io::duration_text(timeout) +
                  " each), so it may not have arrived; " + hint};
    case boards::Failure::HangUp:
      return {ExitCode::DeviceFailure, called + " on " + port + " went away (" + o.detail + ")"};
    case boards::Failure::ReadFailed:
      return {ExitCode::DeviceFailure, "reading from " + port + " failed: " + o.detail};
    case boards::Failure::OtherDialect:
      return {ExitCode::Usage, "the board on " + port + " answers in the " +
                                   std::string(o.answered != nullptr ? o.answered->name : "other") +
                                   " dialect, not as " + called};
    case boards::Failure::Interrupted:
      // Before anything was sent, or while a reply was awaited.
      return {ExitCode::Interrupted, o.awaiting.empty()
                                         ? "interrupted"
                                         : "interrupted while waiting for " + called + "'s reply"};
  }
  return {ExitCode::Internal, "internal: no failure to report"};
}

ExitCode say_port_failure(Context& ctx, const boards::BoardLink& link, const std::string& subject) {
  const BoardError e = port_failure(link.failure, link.request, subject);
  return fail(ctx, e.code, e.message);
}

ExitCode refuse_command(Context& ctx, const boards::Board& board, const std::string& command) {
  ctx.err << "seqc: error: the " << board.name << " board has no " << command << " command"
          << (board.lacks.empty() ? "" : ": ") << board.lacks << "; nothing was sent\n";
  return ExitCode::Usage;
}

std::string times_text(std::uint16_t times) {
  if (times == 0) return "looping until `seqc group stop`";
  return std::to_string(times) + (times == 1 ? " time" : " times");
}

ExitCode exit_code_for(upload::UploadStatus s) {
  switch (s) {
    case upload::UploadStatus::Completed:
      return ExitCode::Ok;
    case upload::UploadStatus::Interrupted:
      return ExitCode::Interrupted;
    case upload::UploadStatus::BadPlan:
      return ExitCode::Internal;
    case upload::UploadStatus::OtherDialect:
      return ExitCode::Usage;
    default:
      return ExitCode::DeviceFailure;
  }
}

std::string other_dialect_text(const boards::Board& board, const compiler::CompileOutput& output) {
  const boards::OtherDialect other = boards::other_dialect(board);
  if (other.answered == nullptr) return "the board on the port is not " + std::string(board.name);
  const std::vector<std::string>& profiles = other.profiles;
  std::string fix = profiles.empty() ? std::string("another profile")
                                     : "a file with `robot: " + profiles.front() + "`";
  if (profiles.size() > 1) {
    std::string rest;
    for (std::size_t i = 1; i < profiles.size(); ++i) rest += (i > 1 ? ", " : "") + profiles[i];
    fix += " (or " + rest + ")";
  }
  const compiler::ServoProgram* program = output.servo_program();
  return "this is an " + std::string(other.answered->name) + " board; the file is for " +
         (program != nullptr ? program->robot.profile : "") + ": use " + fix +
         " for this board, or give --port the port the " + std::string(board.name) + " is on";
}

std::string run_said(const boards::Board& board, const std::optional<boards::RunOutcome>& run) {
  return run && run->started == boards::Confirmation::Reported
             ? std::string(board.called) + " reported it started"
             : std::string(board.unconfirmed_run);
}

std::string first_move_text(const boards::FirstMoveTooFast& fast) {
  return fmt::format(
      "'{}' is at {}; reaching {} in {} is {:.0f} units/s, above its max_speed {:.0f}/s; slow the "
      "first move or pass --force",
      fast.name, fast.from, fast.to, seqc::format_seconds(fast.time_ms), fast.speed,
      fast.max_speed);
}

std::string part_title(const compiler::CompileOutput& output, const std::string& name, int group) {
  const boards::Board& board = boards::board_for(output);
  return board.plan != nullptr ? name + ", group " + std::to_string(group)
                               : name + " (" + std::string(board.name) + ")";
}

}  // namespace seqc::cli
