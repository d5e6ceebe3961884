// What was performing when, as the step walk (step_walk.hpp) goes: every repeat (with when
// each of its passes began), section performance and include it entered, with its time span.
// An error about an instant found only after the walk (the fitted actions outgrowing the groups,
// compiler/targets/servo_controller) names the ones around it, innermost first. Kept small (a
// repeat's pass is one instant, the words made only when asked), since a walk may run 200,000
// steps and a hostile file must stay within its memory budget.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "base/source.hpp"
#include "compiler/frontend/reporter.hpp"
#include "compiler/timeline/exact_time.hpp"

namespace seqc::compiler {

class WalkPerformances {
 public:
  enum class Kind : std::uint8_t { Repeat, Section, Include };
  // `name`: a section's (it outlives the walk's use of this); `times`: a repeat's passes.
  void open(ExactMs now, Location at, Kind kind, const std::string* name = nullptr,
            long long times = 0);
  void pass(ExactMs now) { spans_[open_.back()].passes->push_back(now); }
  void close(ExactMs now);
  // The notes of what contains `t` (start <= t < end), innermost first.
  std::vector<Reporter::Note> at(ExactMs t) const;

 private:
  struct Span {
    ExactMs start, end;
    Location at;
    std::uint32_t depth = 0;
    Kind kind = Kind::Repeat;
    long long times = 0;
    const std::string* name = nullptr;
    // A repeat's: when each pass began (a deque: no doubling slack; none for the others).
    std::shared_ptr<std::deque<ExactMs>> passes;  // shared: a copied walk reads the same
  };
  std::vector<Span> spans_;
  std::vector<std::size_t> open_;  // indices into spans_, outermost first
};

}  // namespace seqc::compiler
