// The servo-controller front end's values: positions with their limits (servos named one by
// one or through a file's groups), exact times through the tempo map, and tolerances.
#include <algorithm>

#include "base/units.hpp"
#include "compiler/targets/servo_controller/servo_lowering_state.hpp"

namespace seqc::compiler {

ScopeChain::ParseEntries ServoLowering::entries_parser() {
  return
      [this](const YamlNode& map, const std::string& where) { return parse_positions(map, where); };
}

std::vector<PositionEntry> ServoLowering::parse_positions(const YamlNode& map,
                                                          const std::string& where) {
  std::vector<PositionEntry> out;
  out.reserve(map.entries.size());
  // How each servo was given so far: not at all, by its name (""), or through a group.
  std::vector<std::optional<std::string>> given(robot_.info.servos.size());
  for (const auto& [key, value] : map.entries) {
    std::vector<std::size_t> outputs;
    const OutputGroup* group = nullptr;
    if (auto it = robot_.names.find(key.scalar); it != robot_.names.end()) {
      outputs.push_back(it->second);
    } else if ((group = scopes_.find_group(key.scalar)) != nullptr) {
      outputs = group->members;
    } else {
      std::vector<std::string> candidates = robot_.name_list();
      for (std::string& g : scopes_.group_names()) candidates.push_back(std::move(g));
      reporter_.unknown(key.location, "servo", key.scalar, candidates, where);
      continue;
    }
    if (outputs.empty()) continue;  // an empty group, reported where it is defined
    auto e = parse_position_entry(key, value, outputs.front(), "500, 90deg, +50", reporter_);
    if (!e) continue;
    for (std::size_t k = 0; k < outputs.size(); ++k) {
      const std::size_t servo = outputs[k];
      if (const std::optional<std::string>& before = given[servo]) {
        const std::string now = group != nullptr ? key.scalar : "";
        std::string how;
        if (!before->empty() && !now.empty()) {
          how = ": through groups '" + *before + "' and '" + now + "'";
        } else if (!before->empty() || !now.empty()) {
          how = ": by name and through group '" + (now.empty() ? *before : now) + "'";
        }
        reporter_.error(key.location, "servo '" + robot_.info.servos[servo].name +
                                          "' is given twice " + where + how);
        continue;
      }
      given[servo] = group != nullptr ? key.scalar : std::string();
      PositionEntry member = *e;
      member.output = servo;
      if (group != nullptr) {
        member.group = key.scalar;
        member.listed_at = group->member_at[k];
      }
      out.push_back(std::move(member));
    }
  }
  return out;
}

void ServoLowering::parse_groups(const YamlNode& groups, FileScope& scope) {
  if (!groups.is_map()) {
    reporter_.error(groups.location,
                    "'groups' must be a map of group names to lists of servos, e.g. "
                    "'groups: {left: [lf_coxa, lm_coxa, lr_coxa]}'");
    return;
  }
  for (const auto& [name, list] : groups.entries) {
    OutputGroup group;
    group.at = name.location;
    if (auto servo = robot_.names.find(name.scalar); servo != robot_.names.end()) {
      const std::string& servo_name = robot_.info.servos[servo->second].name;
      reporter_.error(name.location,
                      "group '" + name.scalar + "' has the name of a servo" +
                          (servo_name == name.scalar ? "" : " ('" + servo_name + "')") +
                          "; a move could not tell them apart: rename the group");
      continue;
    }
    if (!list.is_sequence()) {
      reporter_.error(list.location, "group '" + name.scalar +
                                         "' must be a list of servos, e.g. '" + name.scalar +
                                         ": [lf_coxa, lm_coxa, lr_coxa]'");
    } else if (list.items.empty()) {
      reporter_.error(list.location,
                      "group '" + name.scalar + "' is empty; list the servos it moves");
    }
    for (const YamlNode& member : list.items) {
      auto servo = member.is_scalar() ? robot_.names.find(member.scalar) : robot_.names.end();
      if (!member.is_scalar()) {
        reporter_.error(member.location, "a member of group '" + name.scalar +
                                             "' is a servo name, not " +
                                             std::string(kind_name(member)));
      } else if (servo != robot_.names.end()) {
        const auto listed = std::find(group.members.begin(), group.members.end(), servo->second);
        if (listed != group.members.end()) {
          reporter_.error(member.location, "servo '" + robot_.info.servos[servo->second].name +
                                               "' is listed twice in group '" + name.scalar + "'");
        } else {
          group.members.push_back(servo->second);
          group.member_at.push_back(member.location);
        }
      } else if (groups.find(member.scalar) != nullptr) {
        reporter_.error(member.location, "'" + member.scalar +
                                             "' is a group; a group lists servos, so write its "
                                             "servos here");
      } else {
        reporter_.unknown(member.location, "servo", member.scalar, robot_.name_list(),
                          "in group '" + name.scalar + "'");
      }
    }
    scope.groups[name.scalar] = std::move(group);
  }
}

double ServoLowering::absolute_units(const PositionEntry& e, std::size_t target,
                                     bool reflect) const {
  const ServoInfo& dst = robot_.info.servos[target];
  if (e.home) return dst.home;
  double v = e.value.degrees ? robot_.degrees_to_units(e.value.amount, false) : e.value.amount;
  if (reflect) v = dst.home - (v - robot_.info.servos[e.output].home);
  return v;
}

bool ServoLowering::check_limits(const PositionEntry& e, std::size_t target, double units,
                                 std::string how, std::optional<Reporter::Note> note) {
  const ServoInfo& s = robot_.info.servos[target];
  return check_position_limits(e, s.name, s.min, s.max, units, std::move(how), std::move(note),
                               reporter_);
}

std::optional<ExactMs> ServoLowering::exact_time(const YamlNode& node, std::string_view what) {
  const std::optional<ExactMs> end = musical_time(node, what, now_);
  if (!end) return std::nullopt;
  return *end - now_;
}

std::optional<double> ServoLowering::parse_tolerance(const YamlNode& node) {
  std::string_view text = node.is_scalar() ? std::string_view(node.scalar) : "";
  const bool degrees = text.size() > 3 && text.substr(text.size() - 3) == "deg";
  if (degrees) text.remove_suffix(3);
  double amount = 0;
  if (!node.is_scalar() || !parse_decimal(text, amount) || amount <= 0) {
    reporter_.error(node.location,
                    "'tolerance' must be a positive distance in device units or degrees, e.g. "
                    "'tolerance: 1' or 'tolerance: 0.5deg'");
    return std::nullopt;
  }
  return degrees ? robot_.degrees_to_units(amount, true) : amount;
}

double ServoLowering::tolerance() const {
  for (auto it = lists_.rbegin(); it != lists_.rend(); ++it) {
    if (it->tolerance) return *it->tolerance;
  }
  return scopes_.tolerance().value_or(1.0);
}

}  // namespace seqc::compiler
