#include "compiler/targets/servo_controller/group_budget.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "base/units.hpp"
#include "compiler/frontend/profiles.hpp"

namespace seqc::compiler {

// " at 8.5 s (bar 5 beat 2)": where the action that does not fit starts, on the music's count
// when the file has bars.
std::string when_text(const TempoMap& map, ExactMs t) {
  std::string text =
      " at " + format_seconds(static_cast<std::uint64_t>(std::max<std::int64_t>(0, t.round())));
  if (map.meter_at(t) > 0 && map.bpm_at(t) > 0) {
    const ExactMs beat = map.beat_at(t);
    const ExactMs bar = map.bar_of_beat(beat);
    const std::int64_t whole = bar.num() / bar.den();
    const auto first = map.beat_of_bar(ExactMs(whole));
    if (first) {
      const ExactMs in_bar = beat - *first;
      text += " (bar " + std::to_string(whole + 1) + " beat ";
      if (in_bar.den() == 1) {
        text += std::to_string(in_bar.num() + 1);
      } else {
        text += fmt::format("{:g}", std::floor((in_bar.value() + 1) * 100) / 100);
      }
      text += ")";
    }
  }
  return text;
}

// "the sequence needs at least 1021/1020 actions; a group holds ..., and this step makes action
// 1,021", or for a chained dance "the sequence needs at least 260,101 actions; the 255 groups it
// may take (0-254) hold 260,100 (1,020 each), and this step makes action 260,101".
std::string budget_text(const Robot& robot, std::size_t capacity, std::size_t groups,
                        std::uint64_t needed, bool at_least) {
  const std::string least = at_least ? "at least " : "";
  if (groups <= 1) {
    return "the sequence needs " + least + std::to_string(needed) + "/" + std::to_string(capacity) +
           " actions; " + group_capacity_text(robot.profile);
  }
  const auto n = [](std::uint64_t v) { return format_grouped(static_cast<long long>(v)); };
  const std::uint64_t total = std::uint64_t{capacity} * groups;
  return "the sequence needs " + least + n(needed) + " actions; the " + n(groups) +
         " groups it may take hold " + n(total) + " (" + n(capacity) +
         " each), and this step makes action " + n(total + 1);
}

// Where one group does not hold the dance: how a longer one is stored.
std::optional<Reporter::Note> chain_hint(const ServoWalk& walk) {
  if (walk.groups > 1 || !walk.sequence_at) return std::nullopt;
  return Reporter::Note{*walk.sequence_at,
                        "`seqc upload --run` stores a longer dance as consecutive groups, each "
                        "started on its bar line"};
}

}  // namespace seqc::compiler
