#include "compiler/frontend/step_parts.hpp"

#include <cmath>
#include <cstdio>
#include <map>

#include "compiler/frontend/robot_section.hpp"

namespace seqc::compiler {

std::span<const YamlNode> step_items(const YamlNode& list, std::string_view what,
                                     Reporter& reporter) {
  if (list.kind == YamlNode::Kind::Null) return {};
  if (!list.is_sequence()) {
    reporter.error(list.location, std::string(what) +
                                      " must be a list of steps (each line "
                                      "starting with '- '), not " +
                                      std::string(kind_name(list)));
    return {};
  }
  return list.items;
}

std::optional<RepeatStep> parse_repeat(const YamlNode& step, const YamlNode& count,
                                       Reporter& reporter) {
  auto times = parse_integer(count, 1, 65535, "the repeat count", reporter);
  const YamlNode* body = step.find("do");
  if (body == nullptr) {
    reporter.error(step.location, "'repeat' needs a 'do' list of the steps to repeat");
    return std::nullopt;
  }
  if (!times) return std::nullopt;
  return RepeatStep{*times, body};
}

std::optional<Easing> parse_ease(const YamlNode& node, Reporter& reporter) {
  const EaseParse parsed = node.is_scalar() ? parse_easing(node.scalar) : EaseParse{};
  if (!parsed.easing && parsed.message.empty()) {
    reporter.unknown(node.location, "easing", node.is_scalar() ? node.scalar : "", easing_names(),
                     {}, easing_name_list());
  } else if (!parsed.easing) {
    reporter.error(node.location, parsed.message);
  }
  return parsed.easing;
}

std::string format_ms(double ms) {
  if (ms == std::floor(ms)) return std::to_string(static_cast<long long>(ms)) + "ms";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1fms", ms);
  return buf;
}

}  // namespace seqc::compiler
