// compile_file(): load, read the robot section, and lower for the robot's kind.
#include "compiler/compile.hpp"

#include "compiler/frontend/file_loader.hpp"
#include "compiler/frontend/profiles.hpp"
#include "compiler/frontend/reporter.hpp"
#include "compiler/frontend/robot_section.hpp"
#include "compiler/music/song_check.hpp"
#include "compiler/targets/raspblock/raspblock_lowering.hpp"
#include "compiler/targets/servo_controller/servo_lowering.hpp"

namespace seqc::compiler {
namespace {

// The audio check, for the commands that pass a SongReader and a file with a song.
void check_music(const Timeline& timeline, const CompileOptions& options, Reporter& reporter) {
  if (options.songs == nullptr || !timeline.song) return;
  check_song(*timeline.song, timeline.tempo_map, timeline.end, *options.songs, reporter);
}

}  // namespace

CompileOutput compile_file(const std::string& path, FileReader& files,
                           const CompileOptions& options) {
  CompileOutput out;
  FileLoader loader(files, out.sources, out.diagnostics);
  Reporter reporter(out.diagnostics);
  auto main = loader.load(path);
  if (!main) {
    out.read_error = main.error().message;
    return out;
  }
  const LoadedFile& file = **main;
  if (!file.root) return out;

  std::optional<Robot> robot;
  if (!file.root->is_map()) {
    reporter.error(file.root->location,
                   "a choreography file must be a map with 'robot' and 'sequence' keys");
    return out;
  }
  if (const YamlNode* r = file.root->find("robot")) {
    robot = parse_robot(*r, reporter);
  } else {
    report_missing_robot(*file.root, file.path, reporter);
  }
  if (!robot) return out;

  // Robot kinds plug in here: each kind lowers to its own alternative of Program.
  switch (robot->info.kind) {
    case RobotKind::Raspblock: {
      RaspblockProgram program = lower_raspblock_program(*robot, file, loader, reporter);
      check_music(program.timeline, options, reporter);
      if (!out.diagnostics.has_errors(options.strict)) out.program = std::move(program);
      break;
    }
    case RobotKind::ServoController: {
      ServoProgram program = lower_servo_program(*robot, file, loader, reporter,
                                                 {options.clock_ppm, options.free_end_points});
      check_music(program.timeline, options, reporter);
      if (!out.diagnostics.has_errors(options.strict)) out.program = std::move(program);
      break;
    }
  }
  if (out.program) out.board = robot->info.board;
  return out;
}

}  // namespace seqc::compiler
