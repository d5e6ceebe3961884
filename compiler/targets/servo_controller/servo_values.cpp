// The servo-controller front end's values: positions with their limits, exact times through
// the tempo map, and tolerances.
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
  std::vector<bool> given(robot_.info.servos.size());
  for (const auto& [key, value] : map.entries) {
    auto it = robot_.names.find(key.scalar);
    if (it == robot_.names.end()) {
      reporter_.unknown(key.location, "servo", key.scalar, robot_.name_list(), where);
      continue;
    }
    auto e = parse_position_entry(key, value, it->second, "500, 90deg, +50", reporter_);
    if (!e) continue;
    if (given[e->output]) {
      reporter_.error(key.location,
                      "servo '" + robot_.info.servos[e->output].name + "' is given twice " + where);
      continue;
    }
    given[e->output] = true;
    out.push_back(std::move(*e));
  }
  return out;
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
