// The compiler's driver: a choreography file (docs/language.md) in, a program
// (compiler/program/program.hpp) out.
//
// compile_file() reads the file (and the files it includes) through a FileReader, reports every
// mistake it finds into Diagnostics, and returns a program only when there is no error (with
// options.strict, no warning either). It runs the stages in order: the front end reads the
// file and its robot section, the robot kind's target lowers the steps to a timeline and then to
// actions (fitting) or packets, and the music stage checks the dance against its song. A
// command that takes a choreography or a show calls load() (load.hpp), which reads the file once
// and calls this or load_show() with the text it read.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "base/diagnostics.hpp"
#include "base/source.hpp"
#include "compiler/program/program.hpp"

namespace seqc::compiler {

struct CompileOptions {
  bool strict = false;  // warnings are errors (--strict)
  // Decodes a `music:` song to check the dance against it (docs/music.md); null: no check, so
  // commands that only need the program do not decode audio.
  SongReader* songs = nullptr;
  // The board's clock is this many parts per million fast (slow when negative), as
  // `seqc calibrate clock` measures it: a stored group's action times are pre-scaled so that it
  // lasts the intended time on the host's clock. Every action boundary on the absolute timeline
  // is multiplied by (1 + ppm / 1e6) and then rounded, once (docs/music.md, "Long songs").
  // Only stored servo groups are scaled: a streamed program is timed by the host.
  std::int32_t clock_ppm = 0;
  // Fitting may end an action anywhere within tolerance between knots (docs/language.md,
  // "Curves, tolerance and fitting"); false keeps every target on the rounded curve, the fit
  // before free end points, so that the two can be compared (fit_bench).
  bool free_end_points = true;
  // The stored group will travel over USB HID (`--port hid`, `hid:PATH`, `emu:xarm-hid`): every
  // GroupDownload frame must fit one 64-byte report, so an action naming more servos than one
  // frame holds there is an error at its step (compiler/targets/servo_controller/hid_actions.hpp).
  bool over_hid = false;
  // The dance may take consecutive groups, first_group and on up to the last the board stores
  // (compiler/targets/servo_controller/chain.hpp), when the computer starts each (`upload --run`)
  // or only looks (check, simulate, plot, preview); false: one group, as `compile` writes.
  bool chain = false;
  std::uint8_t first_group = 0;
  // Where the robot stands, for a first move relative to it: read just before the run, or
  // assumed at home with a note (check), or neither (such a move is then an error).
  RobotStart start{};
};

struct CompileOutput {
  SourceManager sources;
  Diagnostics diagnostics;
  std::optional<Program> program;  // set iff !diagnostics.has_errors(options.strict)
  std::string board;               // the program's RobotInfo::board, set with program
  // Set when the main file itself could not be read (a file error, not a mistake in it).
  std::optional<std::string> read_error;

  const ServoProgram* servo_program() const {
    return program ? std::get_if<ServoProgram>(&*program) : nullptr;
  }
  const RaspblockProgram* raspblock_program() const {
    return program ? std::get_if<RaspblockProgram>(&*program) : nullptr;
  }
  // Every file the compile read, in the order it read them: the file given, each file it
  // includes, and its program's song when it has one (an output must be none of them).
  std::vector<std::string> inputs() const;
};

class FileLoader;
class Reporter;
struct LoadedFile;
struct Robot;

// The servo-controller stages for an already loaded file and its robot: the target's walk,
// fitting, and the program made of the fitted actions (errors go to `reporter`).
ServoProgram compile_servo(const Robot& robot, const LoadedFile& file, FileLoader& loader,
                           Reporter& reporter, const CompileOptions& options = {});

// Compiles the file at `path` (as the user wrote it; includes are resolved relative to the
// including file's directory).
CompileOutput compile_file(const std::string& path, FileReader& files,
                           const CompileOptions& options = {});

}  // namespace seqc::compiler
