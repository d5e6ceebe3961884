// One row per board (board_table.cpp): everything seqc does differently for one board is
// reached from here. The CLI asks the table, calls a row's functions and words the results; it
// never compares profile strings, emulator names or frame types. A row's functions return data
// and status values, never text for people, never exit codes. Facts about the board that
// messages need (its name, what it lacks) are row data. Adding a board: a profile row naming
// Board::key (compiler/frontend/profiles.cpp), a runtime/boards/<board>.cpp defining the row, one
// line in board_table.cpp (docs/architecture.md, "Adding a board").
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "compiler/compile.hpp"
#include "protocol/dialects.hpp"
#include "protocol/lsc/lsc_messages.hpp"
#include "protocol/planned_frame.hpp"
#include "runtime/emulator/emulator_serve.hpp"
#include "runtime/io/clock.hpp"
#include "runtime/io/transport.hpp"
#include "runtime/player/player.hpp"
#include "runtime/transport/port_spec.hpp"
#include "runtime/upload/uploader.hpp"

namespace seqc::boards {

struct Hooks;       // hooks.hpp
struct OpenedPort;  // ports.hpp

// A board's link for one command.
struct Line {
  io::Transport& transport;
  io::Clock& clock;
  const std::atomic<bool>* interrupted = nullptr;
  io::Duration timeout = std::chrono::seconds(1);  // per awaited reply (--timeout)
};

// How an exchange ended. The CLI turns it into a sentence and an exit code.
// OtherDialect: the board expected stayed silent and a board of the family's other dialect
// answered its question instead (upload/dialect_questions.hpp); `answered` names that dialect.
enum class Failure {
  None,
  SendFailed,
  NoReply,
  Unconfirmed,
  HangUp,
  ReadFailed,
  Interrupted,
  OtherDialect
};
struct Outcome {
  Failure failure = Failure::None;
  std::string request;   // what was sent, described ("GroupStop", "EraseAll")
  std::string awaiting;  // what was awaited ("the battery voltage", "the erase confirmation")
  std::string detail;    // the link's or transport's own words
  int attempts = 0;      // Unconfirmed: confirmations sent
  const Dialect* answered = nullptr;  // OtherDialect: the dialect that answered
  bool ok() const { return failure == Failure::None; }
};
enum class Confirmation { Reported, NotReported, NeverAnswered };
struct RunOutcome : Outcome {
  Confirmation started = Confirmation::NotReported;
};
struct StopOutcome : Outcome {
  Confirmation stopped = Confirmation::NeverAnswered;
  std::optional<std::uint8_t> group;  // the group the board said it stopped
};

// One timed run of a stored group (seqc calibrate clock): the host time between the board's
// notice that the group started and its notice that it finished, on the line's clock. Both
// notices are frames of one length on one line, so the line's delay cancels out.
struct TimedRun : Outcome {
  io::Duration lasted{0};
};

struct Plan {
  std::uint8_t group = 0;
  std::size_t actions = 0;
  std::vector<PlannedFrame> frames;  // each encoded once (protocol/planned_frame.hpp)
};
enum class Emit { Hex, Listing, Json };
// Which report the CLI words: moves on a servo board, frames on a car.
enum class LiveStyle { Moves, Stream };
enum EmulatorOption : unsigned {
  kBaud = 1u << 0,
  kFaults = 1u << 1,
  kSeed = 1u << 2,
  kPositions = 1u << 3,
  kDumpGroups = 1u << 4,
};

struct Board {
  // identity
  std::string_view key;     // what RobotProfile::board names: "xarm", "lsc6", "raspblock"
  std::string_view name;    // "xArm / LSC-16 / LSC-32", "LSC-6", "Raspblock"
  std::string_view called;  // "the controller", "the board"
  // "servo controller", "Raspblock board": boards that share ports and commands.
  std::string_view family;
  // Its row of the dialect table (protocol/dialects.hpp): what a trace of it names in its header,
  // so `seqc decode` reads the trace in that dialect.
  const Dialect* dialect = nullptr;

  // ports
  std::uint32_t baud = 0;     // a serial port's default rate
  bool over_hid = false;      // `--port hid` reaches it
  bool discoverable = false;  // found without --port

  // seqc compile --emit
  Result<std::string> (*render)(const compiler::CompileOutput&, Emit, std::uint8_t group) = nullptr;

  // storage (all null: the board keeps nothing)
  Result<Plan> (*plan)(const compiler::CompileOutput&, std::uint8_t group) = nullptr;
  upload::UploadResult (*upload)(const Line&, const Plan&, const upload::UploadOptions&,
                                 upload::UploadObserver*) = nullptr;
  Bytes (*acknowledge)(ByteView request) = nullptr;  // the dry run's device
  // The dry run's comment on frame `index` of an upload: "probe: GetBatteryVoltage".
  std::string (*comment)(std::size_t index, ByteView frame) = nullptr;
  std::string_view unconfirmed_run;  // "it did not report starting it"

  // live play
  Result<std::vector<player::ScheduledFrame>> (*live_frames)(const compiler::CompileOutput&) =
      nullptr;
  // Is this board there, and not the family's other dialect (upload/dialect_questions.hpp)?
  // null: nothing can be asked
  Outcome (*probe)(const Line&) = nullptr;
  Bytes (*safe_stop)() = nullptr;  // after an early end; null: none
  bool measure_departure = false;  // drain each frame, report when it left
  bool check_schedule = false;     // refuse a schedule the link cannot keep
  bool wait_for_end = false;       // return when the last move ends
  LiveStyle style = LiveStyle::Moves;
  // Without a probe: "the LSC-6 answers no move, so nothing shows that the board hears them".
  std::string_view unprobed_note;

  // session commands (seqc group, servo move, a show's start)
  std::string_view run_name;  // "GroupRun", "Run"
  Bytes (*run_frame)(std::uint8_t group, std::uint16_t times) = nullptr;
  // From the last byte of its start command (run_frame, or a streamed board's first frame)
  // arriving to the motion starting: a start timed to a song or to other performers subtracts
  // it with the command's wire time. 0 where it has not been measured, which today is every
  // board (docs/music.md).
  io::Duration start_delay{0};
  // After run_frame was written: did the board start the group?
  RunOutcome (*confirm_run)(const Line&, std::uint8_t group, std::uint16_t times) = nullptr;
  std::string_view run_note;  // LSC-6: "the LSC-6 accepts a run before looking at the group: …"
  // Runs `group` once and times it from its start notice to its finish notice (TimedRun),
  // waiting at most `longest` (plus the line's timeout) for the end; null: the board does not
  // announce both, so its clock cannot be measured.
  TimedRun (*time_run)(const Line&, std::uint8_t group, io::Duration longest) = nullptr;
  Bytes (*stop_frame)() = nullptr;
  StopOutcome (*stop)(const Line&) = nullptr;
  // nullopt: every group.
  Outcome (*erase)(const Line&, std::optional<std::uint8_t> group) = nullptr;
  bool erases_one_group = true;  // false: its erase wipes every group (LSC-6)
  Outcome (*move)(const Line&, std::span<const lsc::ServoTarget>, std::uint16_t time_ms) = nullptr;
  bool confirms_moves = true;
  // Battery, servo read/off/mode, offsets, bus-info, group speed (XarmSession).
  bool queries = false;
  // The profile whose names a pose read back from the board uses when --robot gives none.
  std::string_view pose_profile;
  // "its firmware knows only moves, group run/stop, erasing every group and storing actions"
  std::string_view lacks;

  // emulator
  // emu:NAME reaching it; [0] is what `seqc emulate` serves.
  std::span<const std::string_view> emulators;
  bool (*open_emulator)(const transport::PortSpec&, io::Clock& host, const Hooks&, OpenedPort& out,
                        std::string& error) = nullptr;
  emu::ServeResult (*serve)(const emu::ServeOptions&, io::Clock&, const std::atomic<bool>& stop,
                            emu::ServeEvents&) = nullptr;
  unsigned emulator_options = 0;      // EmulatorOption bits `seqc emulate` accepts
  std::string_view no_faults_reason;  // "the Raspblock board never replies"
  std::string_view no_groups_reason;  // "the Raspblock board stores no groups"
};

std::span<const Board* const> all_boards();
const Board* find_board(std::string_view key);
const Board& board_for(const compiler::CompileOutput& output);  // by output.board
const Board* board_for_emulator(std::string_view emulator);     // emu:NAME -> its board
// emu:NAME's board, else the --robot profile's board, else the first discoverable board.
const Board& board_for_device(std::string_view profile, std::string_view port);
bool same_family(const Board& a, const Board& b);
// Whether `port` reaches its board over USB HID, where every frame must fit one report: `hid`,
// `hid:PATH` and the emulator of such a board (emu:xarm-hid); false for any other port and for
// one that does not parse (the command that opens it says why).
bool port_over_hid(std::string_view port);
// The emulator that serves each board of `board`'s family, in table order ("xarm", "lsc6").
std::vector<std::string_view> family_emulators(const Board& board);
// When a file for `board` meets a board of its family that stores in the other dialect
// (UploadStatus::OtherDialect): the family's other storing board (null when it has none), and
// the profiles whose files that board runs, in the profiles' order.
struct OtherDialect {
  const Board* answered = nullptr;
  std::vector<std::string> profiles;
};
OtherDialect other_dialect(const Board& board);
// What `seqc emulate` serves: each board's own emulator, in table order.
std::vector<std::string_view> served_emulators();
// The board a device command (group, servo, battery, offset, bus-info, teach) talks to: the one
// board_for_device finds, when it is of the family discovery finds (the servo controllers);
// else the first discoverable board. So an emulator of another family is refused when its port
// is opened (PortProblem::WrongEmulator), and a --robot profile of another family is ignored.
const Board& board_for_command(std::string_view profile, std::string_view port);

Result<Plan> plan_for(const Board& board, const compiler::CompileOutput& output,
                      std::uint8_t group);
std::optional<std::size_t> first_too_big(const Plan& plan, const io::Transport& transport);
upload::UploadResult upload(const Board& board, const Line& line, const Plan& plan,
                            const upload::UploadOptions& options, upload::UploadObserver* observer);
RunOutcome run_group(const Board& board, const Line& line, std::uint8_t group, std::uint16_t times);

// The first of the `seqc emulate` options `given` (EmulatorOption bits) that `board`'s emulator
// does not take, in the order kFaults, kSeed, kDumpGroups, kPositions, with the row's reason
// when it has one; option 0 when it takes them all. The seed is the faults' seed, so a board
// without faults refuses it too.
struct RefusedOption {
  unsigned option = 0;
  std::string_view reason;  // "the Raspblock board never replies"; may be empty
};
RefusedOption refused_emulator_option(const Board& board, unsigned given);

}  // namespace seqc::boards
