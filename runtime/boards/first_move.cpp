#include "runtime/boards/first_move.hpp"

#include <algorithm>
#include <cstdlib>
#include <set>
#include <vector>

#include "runtime/boards/xarm_queries.hpp"
#include "runtime/boards/xarm_session.hpp"
#include "runtime/upload/controller_link.hpp"

namespace seqc::boards {

std::optional<FirstMoveTooFast> first_move_too_fast(const Board& board, const Line& line,
                                                    const compiler::ServoProgram& program) {
  if (!board.queries) return std::nullopt;
  const std::vector<std::uint8_t> readable = readable_servos(program.robot);
  std::set<std::uint8_t> used;
  for (const compiler::Keyframe& k : program.keyframes) {
    for (const lsc::ServoTarget& t : k.targets) {
      if (std::find(readable.begin(), readable.end(), t.id) != readable.end()) used.insert(t.id);
    }
  }
  if (used.empty()) return std::nullopt;
  upload::ControllerLink link(line.transport, line.clock, line.interrupted);
  XarmSession session(link, line.timeout);
  const auto read = read_positions(session, {used.begin(), used.end()});
  if (!read) return std::nullopt;  // not answered: the play's own probe says why

  std::set<std::uint8_t> seen;
  for (const compiler::Keyframe& k : program.keyframes) {
    for (const lsc::ServoTarget& t : k.targets) {
      if (!seen.insert(t.id).second) continue;  // only each servo's first move
      const auto at = std::find_if(read->begin(), read->end(),
                                   [&](const lsc::ServoTarget& r) { return r.id == t.id; });
      const compiler::ServoInfo* servo = program.robot.find_id(t.id);
      if (at == read->end() || servo == nullptr || !servo->max_speed || k.time_ms == 0) continue;
      const double distance = std::abs(static_cast<double>(t.position) - at->position);
      const double speed = distance * 1000.0 / k.time_ms;
      if (speed > *servo->max_speed) {
        return FirstMoveTooFast{t.id,      servo->name, at->position,     t.position,
                                k.time_ms, speed,       *servo->max_speed};
      }
    }
  }
  return std::nullopt;
}

std::optional<std::map<std::uint8_t, std::uint16_t>> read_start(
    const Board& board, const Line& line, const std::vector<std::uint8_t>& ids) {
  if (!board.queries || ids.empty()) return std::nullopt;
  upload::ControllerLink link(line.transport, line.clock, line.interrupted);
  XarmSession session(link, line.timeout);
  const auto read = read_positions(session, ids);
  if (!read || read->size() != ids.size()) return std::nullopt;
  std::map<std::uint8_t, std::uint16_t> at;
  for (const lsc::ServoTarget& t : *read) at[t.id] = t.position;
  return at;
}

std::optional<FirstMoveTooFast> run_too_fast(const Board& board, const Line& line,
                                             const compiler::CompileOutput& output, bool force) {
  const compiler::ServoProgram* program = output.servo_program();
  if (force || program == nullptr) return std::nullopt;
  return first_move_too_fast(board, line, *program);
}

}  // namespace seqc::boards
