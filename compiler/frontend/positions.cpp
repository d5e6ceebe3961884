#include "compiler/frontend/positions.hpp"

#include <cmath>

#include <fmt/format.h>

namespace seqc::compiler {

std::optional<PositionEntry> parse_position_entry(const YamlNode& key, const YamlNode& value,
                                                  std::size_t output, std::string_view examples,
                                                  Reporter& reporter) {
  PositionEntry e;
  e.output = output;
  e.at = value.location;
  if (!value.is_scalar()) {
    reporter.error(value.location, "the position of '" + key.scalar + "' must be a value such as " +
                                       std::string(examples) + " or home");
    return std::nullopt;
  }
  e.written = value.scalar;
  if (value.scalar == "home") {
    e.home = true;
  } else if (auto p = parse_position(value.scalar); !p) {
    reporter.error(value.location, p.error().message);
    return std::nullopt;
  } else {
    e.value = *p;
  }
  return e;
}

std::optional<Reporter::Note> group_note(const PositionEntry& e, std::string_view name) {
  if (e.group.empty()) return std::nullopt;
  return Reporter::Note{
      e.listed_at,
      fmt::format("'{}' moves through group '{}', which lists it here", name, e.group)};
}

namespace {

// The notes of a message about `e`: where it came through a group, then `note`.
std::vector<Reporter::Note> entry_notes(const PositionEntry& e, std::string_view name,
                                        std::optional<Reporter::Note> note) {
  std::vector<Reporter::Note> notes;
  if (auto g = group_note(e, name)) notes.push_back(std::move(*g));
  if (note) notes.push_back(std::move(*note));
  return notes;
}

}  // namespace

bool check_position_limits(const PositionEntry& e, std::string_view name, long long min,
                           long long max, double units, std::string how,
                           std::optional<Reporter::Note> note, Reporter& reporter) {
  // A value no servo's range comes near (22 digits, 1e300deg) is compared as written: rounded
  // to an integer it would wrap around.
  const bool huge = !(std::fabs(units) < 1e15);
  const long long p = huge ? 0 : std::llround(units);
  if (!huge && p >= min && p <= max) return true;
  if (how.empty() && (e.value.degrees || huge)) how = e.written;
  const bool above = huge ? !(units < 0) : p > max;
  std::string message = huge ? fmt::format("'{}' would move far outside its range", name)
                             : fmt::format("'{}' would move to {}", name, p);
  if (!how.empty()) message += " (" + how + ")";
  message +=
      above ? ", above its max " + std::to_string(max) : ", below its min " + std::to_string(min);
  reporter.error(e.at, std::move(message), entry_notes(e, name, std::move(note)));
  return false;
}

bool check_curve_limits(const Segment& segment, std::string_view name, long long min, long long max,
                        Location at, const std::optional<Reporter::Note>& note,
                        Reporter& reporter) {
  const ValueRange range = value_range(segment);
  const long long low = std::llround(range.low), high = std::llround(range.high);
  if (low >= min && high <= max) return true;
  const std::string curve =
      segment.kind == CurveKind::Eased ? "this " + segment.easing.name() + " curve" : "this curve";
  reporter.error(
      at,
      fmt::format("'{}' would overshoot to {} on {}", name, high > max ? high : low, curve) +
          (high > max ? ", above its max " + std::to_string(max)
                      : ", below its min " + std::to_string(min)),
      note);
  return false;
}

std::optional<double> relative_units(const PositionEntry& e, std::string_view name,
                                     const std::optional<int>& base, double delta, std::string& how,
                                     const std::optional<Reporter::Note>& note,
                                     Reporter& reporter) {
  if (!base) {
    reporter.error(e.at,
                   "'" + std::string(name) + "' has no known position yet, so the relative move '" +
                       e.written + "' has nothing to add to; move it to an absolute position first",
                   entry_notes(e, name, note));
    return std::nullopt;
  }
  if (!(std::fabs(delta) < 1e15)) {
    how = std::to_string(*base) + " " + e.written;
    return delta;  // far outside every range: check_position_limits says so
  }
  const long long d = std::llround(delta);
  how = std::to_string(*base) + (d < 0 ? " " : " +") + std::to_string(d);
  return static_cast<double>(*base + d);
}

}  // namespace seqc::compiler
