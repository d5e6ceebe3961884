#include "compiler/frontend/walk_performances.hpp"

#include <algorithm>

namespace seqc::compiler {

void WalkPerformances::open(ExactMs now, Location at, Kind kind, const std::string* name,
                            long long times) {
  spans_.push_back({now, now, at, static_cast<std::uint32_t>(open_.size()), kind, times, name,
                    kind == Kind::Repeat ? std::make_shared<std::deque<ExactMs>>() : nullptr});
  open_.push_back(spans_.size() - 1);
}

void WalkPerformances::close(ExactMs now) {
  spans_[open_.back()].end = now;
  open_.pop_back();
}

std::vector<Reporter::Note> WalkPerformances::at(ExactMs t) const {
  std::vector<const Span*> in;
  for (const Span& s : spans_) {
    if (s.start <= t && t < s.end) in.push_back(&s);
  }
  std::stable_sort(in.begin(), in.end(),
                   [](const Span* a, const Span* b) { return a->depth > b->depth; });
  std::vector<Reporter::Note> notes;
  for (const Span* s : in) {
    switch (s->kind) {
      case Kind::Repeat: {
        const auto pass =
            std::upper_bound(s->passes->begin(), s->passes->end(), t) - s->passes->begin();
        notes.push_back({s->at, "in pass " + std::to_string(pass) + " of " +
                                    std::to_string(s->times) + " of this repeat"});
        break;
      }
      case Kind::Section:
        notes.push_back({s->at, "in section '" + *s->name + "', performed here"});
        break;
      case Kind::Include:
        notes.push_back({s->at, "included from here"});
        break;
    }
  }
  return notes;
}

}  // namespace seqc::compiler
