// A song's tempo map as `seqc beats` prints it (docs/music.md): where bar 1 beat 1 falls in the
// audio, the meter, and stretches of steady tempo that each start on a bar line. Each stretch's
// beats are exactly evenly spaced (a least-squares line through the detected beats), so beat k
// of a stretch is at start_s + k * 60 / tempo. Pure data and text (also the meter as `--meter 3/4`
// writes it); no analysis here.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace seqc::music {

struct Meter {
  int beats = 4;  // per bar
  int unit = 4;   // the note value of a beat, only printed
  friend bool operator==(const Meter&, const Meter&) = default;
};

// "3/4" -> {3, 4}: 1-16 beats of a whole, half, quarter, eighth or sixteenth note; nullopt for
// anything else.
std::optional<Meter> parse_meter(const std::string& text);

struct TempoStretch {
  int bar = 1;         // the bar it starts on (bar 1 starts at the downbeat)
  double start_s = 0;  // where that bar's first beat falls in the audio
  double tempo = 0;    // beats per minute, as fitted
  int decimals = 0;    // how many decimals of `tempo` the fit supports (0-3)
};

struct TempoMap {
  Meter meter;
  std::vector<TempoStretch> stretches;  // at least one; the first starts on bar 1
  double downbeat_s() const { return stretches.front().start_s; }
};

// The `music:` block, `file` as given (quoted when YAML would read it otherwise):
//   music:
//     file: song.ogg
//     downbeat: 0.750s
//     tempo: 127.96
//     meter: 4/4
//     changes:
//       - {bar: 33, tempo: 132}
std::string music_block(const std::string& file, const TempoMap& map);

// The map as music_block prints it, and so as a choreography pasting that block counts it: the
// downbeat to the millisecond, each tempo to its decimals, and each later stretch starting where
// the bars before it end at those tempos (not where its own fit put it). The click track
// (click_track.hpp) is mixed on this map.
TempoMap as_printed(const TempoMap& map);

// `tempo` with `decimals` decimals, trailing zeros dropped ("128", "127.96").
std::string tempo_text(double tempo, int decimals);

// A beat of the map in the audio: its time, and whether it is a bar's first.
struct MapBeat {
  double time_s = 0;
  bool downbeat = false;
};
// Every beat of the map from `from_s` to `to_s`, including the beats before bar 1 (counted back
// from it at the first stretch's tempo).
std::vector<MapBeat> map_beats(const TempoMap& map, double from_s, double to_s);

}  // namespace seqc::music
