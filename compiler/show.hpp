// Show files: several performers (an arm, a car, ...) on one clock.
//
//   show: duet
//   performers:
//     arm: {file: arm.yaml, port: /dev/ttyUSB0, group: 0}
//     car: {file: car.yaml, port: /dev/ttyAMA0}
//
// Each performer is a choreography file (relative to the show file) and the port it plays on;
// `group` (0-254, default 0) is the action group a servo controller stores it in. A show file
// is recognised by its top-level `show:` key. Loading checks the show file itself (keys, with
// "did you mean") and compiles every performer's file with its own diagnostics.
#pragma once

#include <string>
#include <vector>

#include "compiler/compile.hpp"

namespace seqc::compiler {

struct Performer {
  std::string name;
  std::string file;  // as resolved from the show file's folder
  std::string port;  // "" when the show file gives none
  int group = 0;
  Location at;  // the performer's entry in the show file
  CompileOutput output;
};

struct ShowOutput {
  SourceManager sources;  // the show file itself
  Diagnostics diagnostics;
  std::optional<std::string> read_error;
  std::string name;
  std::vector<Performer> performers;

  bool ok(bool strict = false) const;  // the show file and every performer compiled
  // Every file the show read: the show file, then each performer's CompileOutput::inputs().
  std::vector<std::string> inputs() const;
};

// Whether `text` is a show file (a top-level `show:` key), cheaply, before parsing it
// (load.hpp tells the two kinds of file apart with it).
bool is_show_text(const std::string& text);

// Loading also warns, at the later performer's entry, when two performers' `music:` blocks name
// different songs or downbeats (show_song): a show plays one song, so `seqc show --music`
// refuses it, and the check says it before.
ShowOutput load_show(const std::string& path, FileReader& files,
                     const CompileOptions& options = {});

// The song of a compiled file's `music:` block; nullptr when it has none (or no program).
const Song* song_of(const CompileOutput& compiled);

// The one song of a show's performers: `song` and the first performer naming it (`first`). When
// a later performer names another song or downbeat (same_song), the show has no one song: that
// performer is `other` and its song `other_song`. Without any `music:` block all are nullptr.
struct ShowSong {
  const Song* song = nullptr;
  const Song* other_song = nullptr;
  const Performer* first = nullptr;
  const Performer* other = nullptr;
};
ShowSong show_song(const ShowOutput& show);

// "performers 'arm' and 'car' dance to different songs or downbeats (song.wav at 0.750 s,
// other.wav at 0.800 s)", for a ShowSong with `other`.
std::string different_songs_text(const ShowSong& found);

// Why `show` has no one song to play with it (different_songs_text, "; a show plays one song",
// or that no performer has a `music:` block); "" when `found` (its show_song) is one.
std::string no_one_song(const ShowOutput& show, const ShowSong& found);

}  // namespace seqc::compiler
