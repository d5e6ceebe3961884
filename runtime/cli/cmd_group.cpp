// `seqc group run|stop|erase|speed`: the stored action groups on the servo controller
// (GroupRun, GroupStop, GroupErase, GroupSpeed).
#include <memory>
#include <ostream>
#include <string>
#include <variant>

#include <CLI/CLI.hpp>

#include "runtime/boards/board.hpp"
#include "runtime/boards/servo_args.hpp"
#include "runtime/cli/board_text.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/device_args.hpp"
#include "runtime/cli/device_command.hpp"
#include "runtime/io/time_text.hpp"

namespace seqc::cli {
namespace {

// "every group", "group 3".
std::string target_text(const boards::GroupTarget& t) {
  return t.all ? "every group" : "group " + std::to_string(t.group);
}

struct RunOptions {
  DeviceOptions device;
  std::string group;
  long long times = 1;
  bool forever = false;
  CLI::Option* times_opt = nullptr;
};

ExitCode run_group(Context& ctx, const RunOptions& o) {
  auto group = boards::parse_group(o.group);
  if (!group) return usage_error(ctx, group.error().message);
  const auto counted = boards::run_times(o.times, o.times_opt->count() > 0, o.forever);
  if (!counted) return usage_error(ctx, counted.error().message);
  const std::uint16_t times = *counted;
  const boards::Board& board = boards::board_for_command(o.device.profile(), o.device.port);
  if (board.run_frame == nullptr) return refuse_command(ctx, board, o.device.command);
  return run_on_board(ctx, o.device, board, [&](const boards::Line& line, const std::string& port) {
    const boards::RunOutcome r = boards::run_group(board, line, *group, times);
    if (!r.ok()) return report_outcome(ctx, r, line, port, board);
    const std::string g = "group " + std::to_string(*group);
    switch (r.started) {
      case boards::Confirmation::Reported:
        if (board.run_note.empty()) {
          summarize(ctx, g + " started, " + times_text(times));
        } else {
          // The board answers before it looks at the group: the answer says only that it heard.
          summarize(ctx, g + ": run accepted, " + times_text(times));
          ctx.err << "seqc: note: " << board.run_note << "\n";
        }
        break;
      case boards::Confirmation::NotReported:
        summarize(ctx, g + ": run sent, " + times_text(times));
        ctx.err << "seqc: warning: " << board.called << " did not report " << g
                << " starting; it may be empty (store one with `seqc upload`)\n";
        break;
      case boards::Confirmation::NeverAnswered:
        summarize(ctx, g + ": run sent, " + times_text(times));
        ctx.err << "seqc: warning: no answer within " << io::duration_text(line.timeout) << ": "
                << board.unconfirmed_run << "\n";
        break;
    }
    return ExitCode::Ok;
  });
}

struct StopOptions {
  DeviceOptions device;
};

ExitCode stop_group(Context& ctx, const StopOptions& o) {
  const boards::Board& board = boards::board_for_command(o.device.profile(), o.device.port);
  if (board.stop == nullptr) return refuse_command(ctx, board, o.device.command);
  return run_on_board(ctx, o.device, board, [&](const boards::Line& line, const std::string& port) {
    const boards::StopOutcome r = board.stop(line);
    if (!r.ok()) return report_outcome(ctx, r, line, port, board);
    if (r.stopped == boards::Confirmation::NeverAnswered) {
      summarize(ctx, "stop sent (the " + std::string(board.name) + " does not confirm it)");
    } else {
      summarize(ctx, "stopped" + (r.group ? " (group " + std::to_string(*r.group) + ")" : ""));
    }
    return ExitCode::Ok;
  });
}

struct EraseOptions {
  DeviceOptions device;
  std::string group;
  bool all = false;
};

ExitCode erase_group(Context& ctx, const EraseOptions& o) {
  auto target = boards::erase_target(o.group, o.all);
  if (!target) return usage_error(ctx, target.error().message);
  const boards::Board& board = boards::board_for_command(o.device.profile(), o.device.port);
  if (board.erase == nullptr) return refuse_command(ctx, board, o.device.command);
  if (!target->all && !board.erases_one_group) {
    return usage_error(ctx, "the " + std::string(board.name) +
                                " cannot erase one group: its erase command wipes every group on "
                                "the board, whatever the number; to do that, give --all");
  }
  return run_on_board(ctx, o.device, board, [&](const boards::Line& line, const std::string& port) {
    const std::optional<std::uint8_t> which =
        target->all ? std::nullopt : std::optional<std::uint8_t>(target->group);
    const boards::Outcome r = board.erase(line, which);
    if (!r.ok()) return report_outcome(ctx, r, line, port, board);
    summarize(ctx, target->all ? "every group erased" : target_text(*target) + " erased");
    return ExitCode::Ok;
  });
}

struct SpeedOptions {
  DeviceOptions device;
  std::string group;
  std::string percent;
};

ExitCode speed_group(Context& ctx, const SpeedOptions& o) {
  auto target = boards::parse_group_target(o.group);
  if (!target) return usage_error(ctx, target.error().message);
  auto percent = boards::parse_speed_percent(o.percent);
  if (!percent) return usage_error(ctx, percent.error().message);
  return tell_on_controller(ctx, o.device, lsc::GroupSpeed{target->group, *percent},
                            target_text(*target) + " speed " + std::to_string(*percent) +
                                "% (volatile: back to 100% at power-off)\n");
}

}  // namespace

void add_group_command(CLI::App& app, Context& ctx, Outcome& result) {
  CLI::App* group = app.add_subcommand(
      "group", "Run, stop, erase or re-time the action groups stored on the servo controller");
  group->require_subcommand(1);

  auto run = std::make_shared<RunOptions>();
  CLI::App* run_cmd = group->add_subcommand("run", "Start a stored group (GroupRun)");
  run_cmd->add_option("GROUP", run->group, "Group number 0-254")->required();
  run->times_opt = run_cmd->add_option("--times", run->times, "How many times to play it (1-65535)")
                       ->capture_default_str();
  run_cmd->add_flag("--forever", run->forever, "Loop until `seqc group stop`");
  add_device_options(*run_cmd, run->device);
  run_cmd->callback([run, &ctx, &result] { result.code = run_group(ctx, *run); });

  auto stop = std::make_shared<StopOptions>();
  CLI::App* stop_cmd = group->add_subcommand("stop", "Stop the group that is playing (GroupStop)");
  add_device_options(*stop_cmd, stop->device);
  stop_cmd->callback([stop, &ctx, &result] { result.code = stop_group(ctx, *stop); });

  auto erase = std::make_shared<EraseOptions>();
  CLI::App* erase_cmd =
      group->add_subcommand("erase", "Erase a stored group, or all of them (GroupErase)");
  erase_cmd->add_option("GROUP", erase->group, "Group number 0-254, or `all`");
  erase_cmd->add_flag("--all", erase->all, "Erase every group (the only erase an LSC-6 board has)");
  add_device_options(*erase_cmd, erase->device);
  erase_cmd->callback([erase, &ctx, &result] { result.code = erase_group(ctx, *erase); });

  auto speed = std::make_shared<SpeedOptions>();
  CLI::App* speed_cmd = group->add_subcommand(
      "speed",
      "Play a group faster or slower (GroupSpeed): 100 = as stored, 200 = twice as fast.\n"
      "Volatile: back to 100 at power-off");
  speed_cmd->add_option("GROUP", speed->group, "Group number 0-254, or `all`")->required();
  speed_cmd->add_option("PERCENT", speed->percent, "Speed in percent (1-65535)")
      ->type_name("INT")
      ->required();
  add_device_options(*speed_cmd, speed->device);
  speed_cmd->callback([speed, &ctx, &result] { result.code = speed_group(ctx, *speed); });
}

}  // namespace seqc::cli
