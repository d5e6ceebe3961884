// The sentences and exit statuses runtime/cli/board_text gives what the boards library returns:
// every PortProblem and every Failure, written out here as a person reads them after
// "seqc: error: ", with the status docs/cli.md gives each.
#include <gtest/gtest.h>

#include <chrono>
#include <sstream>

#include "runtime/boards/board.hpp"
#include "runtime/boards/ports.hpp"
#include "runtime/cli/board_text.hpp"

namespace seqc::cli {
namespace {

using boards::Failure;
using boards::PortProblem;
using std::chrono::milliseconds;

const boards::Board& board(const char* key) {
  const boards::Board* b = boards::find_board(key);
  EXPECT_NE(b, nullptr) << key;
  return *b;
}

BoardError port(PortProblem problem, const std::string& text, const char* wanted,
                const char* reached = nullptr, const std::string& subject = "",
                const std::string& detail = "") {
  const boards::PortFailure failure{problem, detail, reached ? &board(reached) : nullptr};
  return port_failure(failure, boards::PortRequest{text, &board(wanted)}, subject);
}

TEST(BoardText, PortProblemsAreUsageOrPortUnavailable) {
  BoardError e = port(PortProblem::Malformed, "emu:", "xarm", nullptr, "", "no emulator named");
  EXPECT_EQ(e.code, ExitCode::Usage);
  EXPECT_EQ(e.message, "--port: no emulator named");

  e = port(PortProblem::EmulatorOptions, "emu:xarm?dorp=1", "xarm", nullptr, "",
           "unknown fault 'dorp'");
  EXPECT_EQ(e.code, ExitCode::Usage);
  EXPECT_EQ(e.message, "--port emu:xarm?dorp=1: unknown fault 'dorp'");

  e = port(PortProblem::NotFound, "", "xarm", nullptr, "", "no controller found");
  EXPECT_EQ(e.code, ExitCode::PortUnavailable);
  EXPECT_EQ(e.message, "no controller found");

  e = port(PortProblem::CannotOpen, "/dev/ttyUSB9", "xarm", nullptr, "", "/dev/ttyUSB9: gone");
  EXPECT_EQ(e.code, ExitCode::PortUnavailable);
  EXPECT_EQ(e.message, "/dev/ttyUSB9: gone");
}

TEST(BoardText, AnEmulatorOfAnotherFamilyNamesWhatFits) {
  // A device command, no file: the emulators of the servo controller family, in table order.
  BoardError e = port(PortProblem::WrongEmulator, "emu:raspblock?seed=2", "xarm", "raspblock");
  EXPECT_EQ(e.code, ExitCode::Usage);
  EXPECT_EQ(e.message,
            "--port emu:raspblock: this command talks to the servo controller; use emu:xarm or "
            "emu:lsc6");
  // With a file: which board the file is for.
  e = port(PortProblem::WrongEmulator, "emu:xarm", "raspblock", "xarm", "car.yaml");
  EXPECT_EQ(e.code, ExitCode::Usage);
  EXPECT_EQ(e.message,
            "--port emu:xarm is the servo controller's emulator; car.yaml is for the raspblock "
            "(use --port emu:raspblock)");
}

TEST(BoardText, HidAndMissingPortsForTheCar) {
  BoardError e = port(PortProblem::WrongKind, "hid", "raspblock");
  EXPECT_EQ(e.code, ExitCode::Usage);
  EXPECT_EQ(e.message,
            "--port hid is a USB HID device (the xArm's link); the Raspblock board is reached "
            "over a serial port at 115200 baud");
  e = port(PortProblem::NeedsPort, "", "raspblock");
  EXPECT_EQ(e.code, ExitCode::Usage);
  EXPECT_EQ(e.message,
            "name the board's serial port with --port, e.g. --port /dev/ttyAMA0 or --port ttyUSB0 "
            "(the board does not announce itself)\n"
            "  hint: --port emu:raspblock plays to the built-in board emulator");
}

TEST(BoardText, EveryFailureHasItsSentenceAndStatus) {
  const auto said = [](Failure f, const char* request, const char* awaiting, const char* detail,
                       int attempts = 0) {
    boards::Outcome o;
    o.failure = f;
    o.request = request;
    o.awaiting = awaiting;
    o.detail = detail;
    o.attempts = attempts;
    return outcome_text(o, "/dev/ttyUSB0", milliseconds(250), "the board");
  };
  BoardError e = said(Failure::SendFailed, "EraseAll", "", "write failed");
  EXPECT_EQ(e.code, ExitCode::DeviceFailure);
  EXPECT_EQ(e.message, "cannot send EraseAll to /dev/ttyUSB0: write failed");

  e = said(Failure::NoReply, "EraseAll", "the erase confirmation", "");
  EXPECT_EQ(e.code, ExitCode::DeviceFailure);
  EXPECT_EQ(e.message,
            "no reply from the board on /dev/ttyUSB0 within 250 ms (waiting for the erase "
            "confirmation); check that the board is powered and connected, and --port");

  e = said(Failure::Unconfirmed, "GroupStop", "", "", 2);
  EXPECT_EQ(e.code, ExitCode::DeviceFailure);
  EXPECT_EQ(e.message,
            "no reply from the board on /dev/ttyUSB0: GroupStop has no answer of its own, and the "
            "battery check sent after it went unanswered (sent 2 times, 250 ms each), so it may "
            "not have arrived; check that the board is powered and connected, and --port");

  e = said(Failure::HangUp, "GroupStop", "confirming GroupStop", "the device went away");
  EXPECT_EQ(e.code, ExitCode::DeviceFailure);
  EXPECT_EQ(e.message, "the board on /dev/ttyUSB0 went away (the device went away)");

  e = said(Failure::ReadFailed, "GroupStop", "confirming GroupStop", "I/O error");
  EXPECT_EQ(e.code, ExitCode::DeviceFailure);
  EXPECT_EQ(e.message, "reading from /dev/ttyUSB0 failed: I/O error");

  e = said(Failure::Interrupted, "GroupStop", "", "");
  EXPECT_EQ(e.code, ExitCode::Interrupted);
  EXPECT_EQ(e.message, "interrupted");
  e = said(Failure::Interrupted, "GroupStop", "confirming GroupStop", "");
  EXPECT_EQ(e.code, ExitCode::Interrupted);
  EXPECT_EQ(e.message, "interrupted while waiting for the board's reply");
}

TEST(BoardText, RefusalNamesTheBoardAndWhatItLacks) {
  std::ostringstream out, err;
  io::ManualClock clock;
  struct NoFiles final : seqc::FileReader {
    Result<std::string> read(const std::string&) override { return make_error("none"); }
  } files;
  Context ctx{out, err, clock, files};
  EXPECT_EQ(refuse_command(ctx, board("lsc6"), "battery"), ExitCode::Usage);
  EXPECT_EQ(err.str(),
            "seqc: error: the LSC-6 board has no battery command: its firmware knows only moves, "
            "group run/stop, erasing every group and storing actions; nothing was sent\n");
}

TEST(BoardText, TimesAndExitCodes) {
  EXPECT_EQ(times_text(1), "1 time");
  EXPECT_EQ(times_text(3), "3 times");
  EXPECT_EQ(times_text(0), "looping until `seqc group stop`");
  EXPECT_EQ(exit_code_for(upload::UploadStatus::Completed), ExitCode::Ok);
  EXPECT_EQ(exit_code_for(upload::UploadStatus::Interrupted), ExitCode::Interrupted);
  EXPECT_EQ(exit_code_for(upload::UploadStatus::BadPlan), ExitCode::Internal);
  EXPECT_EQ(exit_code_for(upload::UploadStatus::NoAnswer), ExitCode::DeviceFailure);
}

}  // namespace
}  // namespace seqc::cli
