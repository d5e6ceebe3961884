// StepTimes (step_times.hpp): the first performance of each step, and how often it ran.
#include "compiler/frontend/step_times.hpp"

namespace seqc::compiler {

std::uint64_t StepTimes::begin(Location at, ExactMs start) {
  const Key k = key(at);
  auto [it, inserted] = steps_.try_emplace(k, StepTime{start, start, 0});
  ++it->second.performances;
  const std::uint64_t token = next_++;
  open_[token] = Open{k, inserted};
  return token;
}

void StepTimes::started(std::uint64_t token, ExactMs start) {
  auto it = open_.find(token);
  if (it == open_.end() || !it->second.first) return;
  steps_[it->second.key].start = start;
}

void StepTimes::end(std::uint64_t token, ExactMs end) {
  auto it = open_.find(token);
  if (it == open_.end()) return;
  if (it->second.first) steps_[it->second.key].end = end;
  open_.erase(it);
}

const StepTime* StepTimes::find(Location at) const {
  auto it = steps_.find(key(at));
  return it == steps_.end() ? nullptr : &it->second;
}

}  // namespace seqc::compiler
