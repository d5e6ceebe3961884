#include "compiler/frontend/rig_file.hpp"

#include <charconv>
#include <cmath>
#include <vector>

#include "base/units.hpp"
#include "compiler/frontend/yaml/yaml_tree.hpp"

namespace seqc::compiler {
namespace {

constexpr std::string_view kKeys[] = {"clock_ppm", "audio_offset"};

Result<std::chrono::nanoseconds> parse_offset(std::string_view text) {
  std::string_view digits = text;
  bool negative = false;
  if (!digits.empty() && (digits.front() == '-' || digits.front() == '+')) {
    negative = digits.front() == '-';
    digits.remove_prefix(1);
  }
  const std::optional<double> ms = seqc::parse_clock_ms(digits);
  if (!ms) return make_error("audio_offset is a time in ms or s, e.g. 40ms or -0.02s");
  const auto ns = static_cast<std::int64_t>(std::llround(*ms * 1e6));
  return std::chrono::nanoseconds{negative ? -ns : ns};
}

}  // namespace

Result<std::int32_t> parse_clock_ppm(std::string_view text) {
  std::string_view digits = text;
  bool negative = false;
  if (!digits.empty() && (digits.front() == '-' || digits.front() == '+')) {
    negative = digits.front() == '-';
    digits.remove_prefix(1);
  }
  std::int64_t v = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
  if (digits.empty() || ec != std::errc{} || end != digits.data() + digits.size()) {
    return make_error("a clock error is a whole number of ppm, e.g. +8000 or -120, not '" +
                      std::string(text) + "'");
  }
  if (v > kMaxRigClockPpm) {
    return make_error("a clock error of " + std::string(text) + " ppm is beyond +-" +
                      std::to_string(kMaxRigClockPpm) + " (20 %)");
  }
  return static_cast<std::int32_t>(negative ? -v : v);
}

std::optional<Rig> parse_rig(const seqc::SourceManager& sources, std::uint32_t file,
                             seqc::Diagnostics& diags) {
  const std::size_t errors_before = diags.error_count();
  auto root = compiler::load_yaml(sources, file, diags);
  if (!root) return std::nullopt;
  Rig rig;
  if (root->kind == compiler::YamlNode::Kind::Null) return rig;  // an empty file: no facts
  if (!root->is_map()) {
    diags.error(root->location, "a rig file is a map, e.g. 'clock_ppm: +8000'");
    return std::nullopt;
  }
  for (const compiler::YamlEntry& e : root->entries) {
    const std::string& key = e.first.scalar;
    const compiler::YamlNode& value = e.second;
    if (key == "clock_ppm" || key == "audio_offset") {
      if (!value.is_scalar()) {
        diags.error(value.location, "'" + key + "' takes one value");
        continue;
      }
      if (key == "clock_ppm") {
        auto ppm = parse_clock_ppm(value.scalar);
        if (!ppm) {
          diags.error(value.location, ppm.error().message);
        } else {
          rig.clock_ppm = *ppm;
        }
      } else {
        auto offset = parse_offset(value.scalar);
        if (!offset) {
          diags.error(value.location, offset.error().message);
        } else {
          rig.audio_offset = *offset;
        }
      }
      continue;
    }
    std::string message = "unknown rig key '" + key + "'";
    const std::string best =
        seqc::did_you_mean(key, std::vector<std::string>(std::begin(kKeys), std::end(kKeys)));
    if (!best.empty()) message += "; did you mean '" + best + "'?";
    message += " (known: clock_ppm, audio_offset)";
    diags.error(e.first.location, message);
  }
  if (diags.error_count() > errors_before) return std::nullopt;
  return rig;
}

}  // namespace seqc::compiler
