#include "compiler/music/tempo_map.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>

#include "base/json_text.hpp"

namespace seqc::music {
namespace {

// Plain YAML scalars need no quotes; anything YAML could read as something else gets them.
std::string yaml_scalar(const std::string& s) {
  bool plain = !s.empty();
  for (char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (!(std::isalnum(u) || c == '.' || c == '_' || c == '-' || c == '/' || u >= 0x80)) {
      plain = false;
    }
  }
  if (plain && (s.front() == '-' || s == "null" || s == "true" || s == "false" || s == "~")) {
    plain = false;
  }
  return plain ? s : seqc::json_string(s);
}

std::string meter_text(const Meter& m) {
  return std::to_string(m.beats) + "/" + std::to_string(m.unit);
}

}  // namespace

std::string tempo_text(double tempo, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, tempo);
  std::string s = buf;
  if (s.find('.') != std::string::npos) {
    while (s.back() == '0') s.pop_back();
    if (s.back() == '.') s.pop_back();
  }
  return s;
}

std::string music_block(const std::string& file, const TempoMap& map) {
  char downbeat[64];
  std::snprintf(downbeat, sizeof downbeat, "%.3fs", map.downbeat_s());
  const TempoStretch& first = map.stretches.front();
  std::string out = "music:\n";
  out += "  file: " + yaml_scalar(file) + "\n";
  out += std::string("  downbeat: ") + downbeat + "\n";
  out += "  tempo: " + tempo_text(first.tempo, first.decimals) + "\n";
  out += "  meter: " + meter_text(map.meter) + "\n";
  if (map.stretches.size() > 1) {
    out += "  changes:\n";
    for (std::size_t i = 1; i < map.stretches.size(); ++i) {
      const TempoStretch& s = map.stretches[i];
      out += "    - {bar: " + std::to_string(s.bar) +
             ", tempo: " + tempo_text(s.tempo, s.decimals) + "}\n";
    }
  }
  return out;
}

TempoMap as_printed(const TempoMap& map) {
  TempoMap out = map;
  for (TempoStretch& s : out.stretches) s.tempo = std::stod(tempo_text(s.tempo, s.decimals));
  out.stretches.front().start_s = std::round(map.downbeat_s() * 1000) / 1000;
  for (std::size_t i = 1; i < out.stretches.size(); ++i) {
    const TempoStretch& before = out.stretches[i - 1];
    out.stretches[i].start_s = before.start_s + double(out.stretches[i].bar - before.bar) *
                                                    map.meter.beats * 60.0 / before.tempo;
  }
  return out;
}

std::vector<MapBeat> map_beats(const TempoMap& map, double from_s, double to_s) {
  std::vector<MapBeat> beats;
  const int per_bar = map.meter.beats;
  const TempoStretch& first = map.stretches.front();
  const double first_period = 60.0 / first.tempo;
  // Before bar 1: whole beats back from the downbeat.
  const auto before = static_cast<long long>(std::floor((first.start_s - from_s) / first_period));
  for (long long k = before; k >= 1; --k) {
    const double t = first.start_s - double(k) * first_period;
    const long long index = -k;
    beats.push_back({t, ((index % per_bar) + per_bar) % per_bar == 0});
  }
  for (std::size_t i = 0; i < map.stretches.size(); ++i) {
    const TempoStretch& s = map.stretches[i];
    const double period = 60.0 / s.tempo;
    const bool last = i + 1 == map.stretches.size();
    const long long count =
        last ? static_cast<long long>(std::floor((to_s - s.start_s) / period)) + 1
             : static_cast<long long>(map.stretches[i + 1].bar - s.bar) * per_bar;
    for (long long k = 0; k < count; ++k) {
      const double t = s.start_s + double(k) * period;
      if (t >= from_s && t <= to_s) beats.push_back({t, k % per_bar == 0});
    }
  }
  return beats;
}

std::optional<Meter> parse_meter(const std::string& text) {
  int beats = 0, unit = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%d/%d%c", &beats, &unit, &tail) != 2) return std::nullopt;
  if (beats < 1 || beats > 16) return std::nullopt;
  if (unit != 1 && unit != 2 && unit != 4 && unit != 8 && unit != 16) return std::nullopt;
  return Meter{beats, unit};
}

}  // namespace seqc::music
