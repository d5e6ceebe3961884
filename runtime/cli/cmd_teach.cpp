// seqc teach FILE.yaml [--port P]: teach-in. The servos go limp (MultiServoOff) so the robot can
// be posed by hand; each Enter reads every servo's position (ServoPositionRead) and adds it to
// the file's `poses:` as a named pose, editing the text (pose_text.hpp) so the file's comments
// and layout stay as they were; `q` (or end of input) finishes. Prompts and reports go to
// stderr; the file is rewritten atomically after each pose, so nothing taught is lost.
#include <istream>
#include <string>

#include <CLI/CLI.hpp>

#include "compiler/formats/pose_text.hpp"
#include "compiler/frontend/robot_section.hpp"
#include "runtime/boards/xarm_queries.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/device_command.hpp"
#include "runtime/io/disk.hpp"

namespace seqc::cli {
namespace {

struct TeachOptions {
  std::string file;
  DeviceOptions device;
};

bool read_line(Context& ctx, std::string& line) {
  return ctx.in != nullptr && static_cast<bool>(std::getline(*ctx.in, line));
}

ExitCode teach(Context& ctx, const TeachOptions& o) {
  auto read = ctx.files.read(o.file);
  if (!read) {
    return fail(ctx, ExitCode::FileError,
                read.error().message +
                    " (teach adds poses to an existing file; start one with a `robot:` line)");
  }
  std::string text = std::move(*read);
  seqc::SourceManager sources;
  seqc::Diagnostics diags;
  const std::optional<compiler::RobotInfo> robot =
      compiler::robot_of_text(o.file, text, sources, diags);
  if (!robot) {
    ctx.err << seqc::render_all(diags, sources, false, ctx.color);
    return ExitCode::InvalidInput;
  }
  const std::vector<std::uint8_t> ids = boards::readable_servos(*robot);
  if (ids.empty()) {
    return fail(ctx, ExitCode::InvalidInput,
                o.file + ": robot '" + robot->profile +
                    "' has PWM servos, which cannot report where they are; teach needs bus "
                    "servos (xarm, bus)");
  }
  int added = 0;
  const ExitCode code = run_on_controller(ctx, o.device, [&](boards::XarmSession& s) {
    if (!s.tell(lsc::MultiServoOff{ids})) return ExitCode::DeviceFailure;
    ctx.err << "seqc: the servos are limp: pose the robot by hand.\n";
    for (;;) {
      ctx.err << "seqc: press Enter to record the pose, q to finish: " << std::flush;
      std::string line;
      if (!read_line(ctx, line) || line == "q" || line == "Q") break;
      auto answered = boards::read_positions(s, ids);
      if (!answered) return ExitCode::DeviceFailure;
      std::vector<std::pair<std::uint8_t, std::uint16_t>> positions;
      for (const lsc::ServoTarget& t : *answered) positions.emplace_back(t.id, t.position);
      if (positions.size() != ids.size()) {
        ctx.err << "seqc: warning: " << ids.size() - positions.size()
                << " servo(s) did not answer; recording the others\n";
      }
      std::string name;
      const std::string fallback = compiler::next_pose_name(text);
      for (;;) {
        ctx.err << "seqc: name [" << fallback << "]: " << std::flush;
        if (!read_line(ctx, name) || name.empty()) name = fallback;
        if (compiler::is_pose_name(name)) break;
        ctx.err << "seqc: a pose name is letters, digits and _, not starting with a digit\n";
      }
      const std::string pose = compiler::pose_line(name, positions, *robot);
      auto edited = compiler::add_pose(text, pose, name);
      if (!edited) {
        ctx.err << "seqc: error: " << o.file << ": " << edited.error().message << "\n";
        continue;
      }
      if (auto ok = io::write_file_safely(o.file, *edited); !ok) {
        return fail(ctx, ExitCode::FileError, ok.error().message);
      }
      text = std::move(*edited);
      ++added;
      summarize(ctx, "added " + pose);
    }
    return ExitCode::Ok;
  });
  summarize(ctx, std::to_string(added) + " pose" + (added == 1 ? "" : "s") + " added to " + o.file +
                     "; the servos stay limp until they are moved again");
  return code;
}

}  // namespace

void add_teach_command(CLI::App& app, Context& ctx, Outcome& result) {
  auto o = std::make_shared<TeachOptions>();
  CLI::App* cmd = app.add_subcommand(
      "teach", "Pose the robot by hand and add each pose to a choreography's poses (teach-in)");
  cmd->add_option("FILE", o->file, "Choreography file (.yaml) to add the poses to")->required();
  add_device_options(*cmd, o->device);
  cmd->callback([&ctx, &result, o] { result.code = teach(ctx, *o); });
}

}  // namespace seqc::cli
