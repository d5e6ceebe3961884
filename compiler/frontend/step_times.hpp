// When each written step ran, as the step walk (step_walk.hpp) timed it: for tools that show a
// file's timing beside its text (the language server's inlay hints and hovers). A step performed
// several times (a repeat's passes, a section performed twice) keeps its first performance and
// a count. Recording is optional and changes nothing in the walk: a walker without a StepTimes
// records nothing.
#pragma once

#include <cstdint>
#include <map>
#include <tuple>

#include "base/source.hpp"
#include "compiler/timeline/exact_time.hpp"

namespace seqc::compiler {

struct StepTime {
  ExactMs start;  // when the step starts (after its `at:` gap), from the start of the sequence
  ExactMs end;    // when the list goes on after it
  std::uint64_t performances = 0;
};

class StepTimes {
 public:
  using Key = std::tuple<std::uint32_t, std::uint32_t, std::uint32_t>;  // file, line, column
  static Key key(Location at) { return {at.file, at.line, at.column}; }

  // A step at `at` begins at `start`; its end and a later `at:` gap are set by the calls below
  // with the token returned here.
  std::uint64_t begin(Location at, ExactMs start);
  // The step begun with `token` really starts at `start` (its `at:` held until then).
  void started(std::uint64_t token, ExactMs start);
  void end(std::uint64_t token, ExactMs end);

  // The first performance of the step written at `at`, or nullptr when none was walked.
  const StepTime* find(Location at) const;
  const std::map<Key, StepTime>& all() const { return steps_; }

 private:
  std::map<Key, StepTime> steps_;
  // The steps being walked (a step holds steps), each its key and whether this is its first
  // performance (only that one's times are kept).
  struct Open {
    Key key;
    bool first = false;
  };
  std::map<std::uint64_t, Open> open_;
  std::uint64_t next_ = 0;
};

}  // namespace seqc::compiler
