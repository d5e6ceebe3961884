#include "runtime/cli/run_compile.hpp"

#include <map>
#include <optional>
#include <utility>

#include "runtime/boards/board_link.hpp"
#include "runtime/boards/first_move.hpp"
#include "runtime/boards/trace_file.hpp"
#include "runtime/cli/board_text.hpp"
#include "runtime/cli/commands.hpp"

namespace seqc::cli {

Compiled compile_for_run(Context& ctx, const std::string& path, bool strict,
                         const std::string& port, const ClockScaleOptions* clock) {
  std::int32_t ppm = 0;
  if (clock != nullptr) {
    if (const ExitCode e = resolve_clock_ppm(ctx, *clock, ppm); e != ExitCode::Ok) return {{}, e};
  }
  // Taking the robot to stand at home first, to learn which servos to read; a file with
  // mistakes or without such a move is said and ends here.
  compiler::RobotStart assumed;
  assumed.assume_home = true;
  Compiled first = compile_quietly(ctx, path, strict, SongCheck::Skip, ppm, false, true, assumed);
  first.clock_ppm = ppm;
  const compiler::ServoProgram* program = first.output.servo_program();
  if (program == nullptr || program->start_reads.empty()) {
    report_compile(ctx, first, strict);
    return first;
  }
  const boards::Board& board = boards::board_for(first.output);
  const std::vector<std::uint8_t> ids = program->start_reads;
  std::optional<std::map<std::uint8_t, std::uint16_t>> read;
  {
    boards::TraceFile no_trace;
    const boards::BoardLink link =
        boards::open_link({port, &board}, no_trace, ctx.clock, ctx.hooks, ctx.interrupted);
    if (!link.port) return {{}, say_port_failure(ctx, link, path)};
    read = boards::read_start(board, *link.line, ids);
  }
  if (!read) {
    std::string names;
    for (std::uint8_t id : ids) {
      const compiler::ServoInfo* s = program->robot.find_id(id);
      names += (names.empty() ? "'" : ", '") + (s != nullptr ? s->name : std::to_string(id)) + "'";
    }
    return {{},
            fail(ctx, ExitCode::DeviceFailure,
                 path + ": cannot read where " + names +
                     " stand (the controller did not answer ServoPositionRead); their first "
                     "moves are relative to it, so nothing was sent")};
  }
  compiler::RobotStart start;
  start.read = std::move(*read);
  Compiled c =
      compile_quietly(ctx, path, strict, SongCheck::Skip, ppm, false, true, std::move(start));
  c.clock_ppm = ppm;
  report_compile(ctx, c, strict);
  return c;
}

}  // namespace seqc::cli
