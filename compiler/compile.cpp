// compile_file(): the stages in order. The front end loads the file and reads its robot
// section; the robot kind's target walks the steps to a timeline; fitting makes actions of a
// servo controller's timeline and the target makes the program of them (the car's packets need
// no fitting); the music stage checks the dance against its song.
#include "compiler/compile.hpp"

#include "base/units.hpp"
#include "compiler/fitting/fitter.hpp"
#include "compiler/frontend/file_loader.hpp"
#include "compiler/frontend/profiles.hpp"
#include "compiler/frontend/reporter.hpp"
#include "compiler/frontend/robot_section.hpp"
#include "compiler/music/song_check.hpp"
#include "compiler/targets/raspblock/raspblock_lowering.hpp"
#include "compiler/targets/servo_controller/chain.hpp"
#include "compiler/targets/servo_controller/hid_actions.hpp"
#include "compiler/targets/servo_controller/servo_lowering.hpp"

namespace seqc::compiler {
namespace {

// The audio check, for the commands that pass a SongReader and a file with a song.
// A song whose block or dance has mistakes is only read, so that an unreadable file is said in
// the same run as those mistakes.
void check_music(const Timeline& timeline, const CompileOptions& options, Reporter& reporter) {
  if (options.songs == nullptr) return;
  if (timeline.song) {
    check_song(*timeline.song, timeline.tempo_map, timeline.end, *options.songs, reporter);
  } else if (timeline.song_file) {
    check_song_readable(*timeline.song_file, *options.songs, reporter);
  }
}

// A dance over one group's capacity, cut as `upload --run` will cut it: the groups' bars, or
// why they cannot be stored.
void check_chain(ServoProgram& program, std::int32_t clock_ppm, Location sequence_at,
                 Reporter& reporter) {
  auto cut = chain_groups(program, program.group_capacity, clock_ppm);
  if (!cut) {
    reporter.error(sequence_at, "this dance cannot be cut into groups: " + cut.error().message);
    return;
  }
  if (cut->pieces.size() > program.groups) {
    const ResyncPiece& first_out = cut->pieces[program.groups];
    const std::int64_t bar = cut->bars[program.groups];
    reporter.error(sequence_at,
                   "this dance needs " + std::to_string(cut->pieces.size()) +
                       " groups, and the board stores " + std::to_string(program.groups) +
                       " from the first one; group " + std::to_string(program.groups + 1) +
                       " would start at " + format_seconds(first_out.board_start_ms) +
                       (bar > 0 ? " (bar " + std::to_string(bar) + ")" : std::string()));
    return;
  }
  program.group_bars = std::move(cut->bars);
}

}  // namespace

std::vector<std::string> CompileOutput::inputs() const {
  std::vector<std::string> files;
  for (std::uint32_t f = 0; f < sources.file_count(); ++f) files.push_back(sources.path(f));
  const Song* song = nullptr;
  if (const ServoProgram* p = servo_program(); p && p->timeline.song) {
    song = &*p->timeline.song;
  } else if (const RaspblockProgram* r = raspblock_program(); r && r->timeline.song) {
    song = &*r->timeline.song;
  }
  if (song != nullptr) files.push_back(song->file);
  return files;
}

ServoProgram compile_servo(const Robot& robot, const LoadedFile& file, FileLoader& loader,
                           Reporter& reporter, const CompileOptions& options) {
  const std::size_t stored = stored_groups(robot.profile);
  const std::size_t groups =
      options.chain && options.first_group < stored ? stored - options.first_group : 1;
  ServoWalk walk = walk_servo_file(robot, file, loader, reporter, groups, options.start);
  if (!ready_to_fit(walk, robot, reporter)) {
    ServoProgram unfitted;
    unfitted.robot = robot.info;
    unfitted.timeline.song_file = walk.timeline.song_file;
    unfitted.group_capacity = walk.capacity;
    unfitted.groups = walk.groups;
    return unfitted;
  }
  const FitResult fit = fit_timeline_on_board(
      walk.timeline, servo_fit_options(robot, options.free_end_points), options.clock_ppm);
  const std::optional<Location> sequence_at = walk.sequence_at;
  ServoProgram program = servo_program(robot, std::move(walk), fit, options.clock_ppm, reporter);
  if (options.over_hid) check_hid_actions(program, reporter);
  if (program.keyframes.size() > program.group_capacity && reporter.errors_reported() == 0) {
    check_chain(program, options.clock_ppm, sequence_at.value_or(Location{}), reporter);
  }
  return program;
}

CompileOutput compile_file(const std::string& path, FileReader& files,
                           const CompileOptions& options) {
  CompileOutput out;
  FileLoader loader(files, out.sources, out.diagnostics);
  Reporter reporter(out.diagnostics);
  reporter.set_alias_uses(&loader.alias_uses());
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
      ServoProgram program = compile_servo(*robot, file, loader, reporter, options);
      check_music(program.timeline, options, reporter);
      if (!out.diagnostics.has_errors(options.strict)) out.program = std::move(program);
      break;
    }
  }
  if (out.program) out.board = robot->info.board;
  return out;
}

}  // namespace seqc::compiler
