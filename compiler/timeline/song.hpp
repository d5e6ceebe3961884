// The song a choreography dances to, as its `music:` block writes it: the audio file (resolved
// relative to the choreography), where bar 1 beat 1 falls in the audio (the sequence's time 0
// is that instant), and the song's tempo map as written (tempo and meter at bar 1, then the
// changes by bar; a tempo may name the note it counts). Later stages (plot, play, the audio check)
// read it; the front end has already turned it into the timeline's TempoMap.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "base/source.hpp"
#include "compiler/timeline/exact_time.hpp"
#include "compiler/timeline/tempo_map.hpp"

namespace seqc::compiler {

struct SongChange {
  long long bar = 1;                   // counted from 1, as written
  std::optional<Tempo> tempo;          // the tempo from this bar on, if it changes here
  std::optional<TimeSignature> meter;  // the meter from this bar on, if it changes here
  Location at;
};

// The audio file a `music:` block names, known also when the rest of the block has mistakes.
struct SongFile {
  std::string path;  // resolved relative to the choreography
  Location at;       // the `file:` value
};

struct Song {
  std::string file;     // the audio file's path, resolved relative to the choreography
  ExactMs downbeat;     // where bar 1 beat 1 (time 0 of the sequence) falls in the audio
  Tempo tempo;          // at bar 1, as written
  TimeSignature meter;  // at bar 1
  std::vector<SongChange> changes;  // bars strictly increasing, each after bar 1
  Location at;                      // the `music:` key, for diagnostics about the song
  Location file_at;                 // the `file:` value

  // The tempo at bar 1 in beats of its meter a minute (a dotted quarter = 60 in 6/8 is 180).
  double bpm() const {
    const ExactMs beat = beat_ms(tempo, meter.beat_unit);
    return beat > ExactMs(0) ? (ExactMs(60000) / beat).value() : 0;
  }
};

// Whether two `music:` blocks name one song, as a show plays it: the same file with bar 1 beat 1
// at the same instant of it (the tempo maps may differ: each performer counts its own beats).
inline bool same_song(const Song& a, const Song& b) {
  return a.file == b.file && a.downbeat == b.downbeat;
}

}  // namespace seqc::compiler
