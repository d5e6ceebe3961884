// `seqc calibrate clock`: how fast a board's own clock runs against the host's. A group of known
// length (actions holding the servos where they are, read first where the board can say; on a
// board that cannot, actions naming no servo) is
// stored, run several times, and each run timed from the board's start notice to its finish
// notice (Board::time_run) on the line's clock. A board whose clock is e fast plays a group of
// N board milliseconds in N / (1 + e) host milliseconds, so each run gives
// e = N / host - 1; the result is their mean and their spread. Returns data only: the CLI
// words it (and the line for a rig file, docs/music.md).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "base/result.hpp"
#include "protocol/lsc/lsc_messages.hpp"
#include "runtime/boards/board.hpp"
#include "runtime/upload/uploader.hpp"

namespace seqc::boards {

struct ClockSettings {
  std::uint8_t group = 0;        // the group the measuring actions are stored in (overwritten)
  std::uint32_t run_ms = 20000;  // one run's length on the board's clock
  std::size_t runs = 5;
  std::vector<std::uint8_t> servos = {1, 2, 3, 4, 5, 6};  // read and held (xArm: 6 bus servos)
  // Where a controller with position reads holds the servos when none answered. A board
  // without them (the LSC-6) gets actions naming no servo: it moves nothing.
  std::uint16_t fallback_position = 500;
};

struct ClockMeasurement {
  // The first thing that went wrong: the upload (upload.ok() false) or a run (failure).
  upload::UploadResult upload;
  Outcome failure;
  std::vector<lsc::ServoTarget> held;  // the positions the group holds
  bool positions_read = false;         // held comes from the board (else see fallback_position)
  std::vector<io::Duration> lasted;    // each run's host time
  std::vector<double> ppm;             // each run's error
  double mean_ppm = 0;
  double spread_ppm = 0;  // the runs' sample standard deviation (0 for one run)
  bool ok() const { return upload.ok() && failure.ok() && !ppm.empty(); }
};

// The clock error, in ppm, of a board that played `board_ms` of its own in `host` (>0).
double clock_error_ppm(std::uint32_t board_ms, io::Duration host);

// The actions the measuring group holds `targets` with: `run_ms` in a few equal actions (at
// least four, none over 30 s), the remainder in the last.
std::vector<compiler::Keyframe> holding_keyframes(const std::vector<lsc::ServoTarget>& targets,
                                                  std::uint32_t run_ms);

// Requires board.time_run and board.plan. Stores the group (overwriting settings.group), then
// times settings.runs runs.
ClockMeasurement measure_clock(const Board& board, const Line& line, const ClockSettings& settings);

// `--length`: one run's length as whole milliseconds from 1 s to 10 minutes ("20s", "1500ms");
// an error naming --length otherwise, ready for "seqc: error: ".
Result<std::uint32_t> parse_run_length(const std::string& text);

}  // namespace seqc::boards
