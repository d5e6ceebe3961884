#include "compiler/lang/step_parts.hpp"

#include <cmath>
#include <cstdio>
#include <map>

#include "compiler/lang/robot_section.hpp"

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

double ease_at(Ease ease, double t) {
  switch (ease) {
    case Ease::Linear:
      return t;
    case Ease::In:
      return t * t;
    case Ease::Out:
      return 1 - (1 - t) * (1 - t);
    case Ease::InOut:
      return t < 0.5 ? 2 * t * t : 1 - 2 * (1 - t) * (1 - t);
  }
  return t;
}

std::optional<Ease> parse_ease(const YamlNode& node, Reporter& reporter) {
  static const std::map<std::string, Ease, std::less<>> kEases = {
      {"linear", Ease::Linear},     {"in", Ease::In},      {"out", Ease::Out},
      {"in-out", Ease::InOut},      {"ease-in", Ease::In}, {"ease-out", Ease::Out},
      {"ease-in-out", Ease::InOut},
  };
  auto it = node.is_scalar() ? kEases.find(node.scalar) : kEases.end();
  if (it == kEases.end()) {
    reporter.unknown(node.location, "easing", node.is_scalar() ? node.scalar : "",
                     {"linear", "in", "out", "in-out"});
    return std::nullopt;
  }
  return it->second;
}

std::string format_ms(double ms) {
  if (ms == std::floor(ms)) return std::to_string(static_cast<long long>(ms)) + "ms";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1fms", ms);
  return buf;
}

}  // namespace seqc::compiler
