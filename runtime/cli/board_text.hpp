// The words for what runtime/boards returns: a port that could not be opened, an exchange that
// failed, an upload's status, each turned into the sentence after "seqc: error: " and the exit
// status docs/cli.md gives it. The boards library returns status values and facts about a board
// (its name, what it lacks); the sentences are composed here from those facts, so no command
// branches on which board it has. The title plot and preview give a program is one of them.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "runtime/boards/board.hpp"
#include "runtime/boards/board_link.hpp"
#include "runtime/boards/first_move.hpp"
#include "runtime/boards/ports.hpp"
#include "runtime/cli/context.hpp"
#include "runtime/cli/exit_codes.hpp"
#include "runtime/io/clock.hpp"
#include "runtime/upload/uploader.hpp"

namespace seqc::cli {

// A sentence for "seqc: error: " and the exit status that goes with it.
struct BoardError {
  ExitCode code = ExitCode::DeviceFailure;
  std::string message;
};

// Why --port did not open. `subject` names the file the command was given ("walk.yaml"), for the
// sentence that says which board it is for; "" when the command has no file.
BoardError port_failure(const boards::PortFailure& failure, const boards::PortRequest& request,
                        const std::string& subject);

// Says port_failure's sentence for `link`'s port, which did not open, after "seqc: error: " on
// ctx.err; returns its exit status.
ExitCode say_port_failure(Context& ctx, const boards::BoardLink& link, const std::string& subject);

// Why an exchange on `port` (the transport's description) failed. `called` is how the sentence
// names the far end ("the controller", "the board"); `timeout` is the per-reply wait it quotes.
BoardError outcome_text(const boards::Outcome& outcome, const std::string& port,
                        io::Duration timeout, std::string_view called);

// What `board` said of a run it was sent: "the controller reported it started", else its words
// for a start it did not report (Board::unconfirmed_run).
std::string run_said(const boards::Board& board, const std::optional<boards::RunOutcome>& run);

// Why a start was refused (boards/first_move.hpp): "'base' is at 120; reaching 880 in 0.5 s is
// 1520 units/s, above its max_speed 800/s; slow the first move or pass --force".
std::string first_move_text(const boards::FirstMoveTooFast& fast);

// "seqc: error: the LSC-6 board has no battery command: ...; nothing was sent" on ctx.err, for a
// command `board` has no way to answer; returns ExitCode::Usage.
ExitCode refuse_command(Context& ctx, const boards::Board& board, const std::string& command);

// "1 time", "3 times", or "looping until `seqc group stop`" for 0.
std::string times_text(std::uint16_t times);

// An upload that did not complete: Interrupted, Internal (a bad plan), Usage (the board on the
// port speaks the family's other dialect: the file is for another board) or DeviceFailure.
ExitCode exit_code_for(upload::UploadStatus status);

// UploadStatus::OtherDialect, for `output` (a file of a profile) meant for `board`: "this is an
// LSC-6 board; the file is for xarm: use a file with `robot: lsc-6` for this board, or give
// --port the port the xArm / LSC-16 / LSC-32 is on" (boards::other_dialect).
std::string other_dialect_text(const boards::Board& board, const compiler::CompileOutput& output);

// How `seqc plot` and `seqc preview` title a program's picture: the group a stored program is
// for ("walk.yaml, group 2"), else the board that plays it ("car.yaml (Raspblock)").
std::string part_title(const compiler::CompileOutput& output, const std::string& name, int group);

}  // namespace seqc::cli
