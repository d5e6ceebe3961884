#include "runtime/boards/live_moves.hpp"

#include <map>

namespace seqc::boards {

std::vector<LiveMove> changed_moves(const compiler::ServoProgram& program) {
  std::map<std::uint8_t, std::uint16_t> sent;  // each servo's last target sent
  std::vector<LiveMove> out;
  out.reserve(program.keyframes.size());
  for (const compiler::Keyframe& k : program.keyframes) {
    LiveMove m{k.start_ms, k.time_ms, {}};
    for (const lsc::ServoTarget& t : k.targets) {
      auto it = sent.find(t.id);
      if (it == sent.end() || it->second != t.position) m.targets.push_back(t);
    }
    // An opening rest (no servo named yet) sends nothing: the servos stay where they stand
    // until the first move, which keeps its own start.
    if (k.targets.empty() && sent.empty()) continue;
    if (m.targets.empty()) {
      // Nothing changes: one servo where it already is keeps the move on the schedule.
      if (!k.targets.empty()) {
        m.targets.push_back(k.targets.front());
      } else if (!sent.empty()) {
        m.targets.push_back({sent.begin()->first, sent.begin()->second});
      }
    }
    for (const lsc::ServoTarget& t : m.targets) sent[t.id] = t.position;
    out.push_back(std::move(m));
  }
  return out;
}

}  // namespace seqc::boards
