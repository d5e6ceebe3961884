// Pieces of a step that read the same for every robot kind: the list of steps, `repeat` with
// its `do` list, `ease`, and how step times are written in messages.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "compiler/frontend/reporter.hpp"
#include "compiler/frontend/yaml/yaml_tree.hpp"
#include "compiler/timeline/easing.hpp"

namespace seqc::compiler {

// The steps of `list` (called `what` in messages): none for an empty value, and none after
// reporting anything but a list.
std::span<const YamlNode> step_items(const YamlNode& list, std::string_view what,
                                     Reporter& reporter);

struct RepeatStep {
  long long times = 0;
  const YamlNode* body = nullptr;  // the 'do' list
};

// `repeat: <count>` with its 'do' list; nullopt after reporting.
std::optional<RepeatStep> parse_repeat(const YamlNode& step, const YamlNode& count,
                                       Reporter& reporter);

// The value of 'ease' (compiler/timeline/easing.hpp); nullopt after reporting an unknown name
// with "did you mean", or what is wrong with a cubic-bezier.
std::optional<Easing> parse_ease(const YamlNode& node, Reporter& reporter);

// "25ms", "12.5ms": a step's share of a move, for messages.
std::string format_ms(double ms);

}  // namespace seqc::compiler
