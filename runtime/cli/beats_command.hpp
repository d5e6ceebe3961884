// `seqc beats SONG`: the song's tempo map as a `music:` block (docs/music.md), from the audio
// interfaces it is given, so tests run it on samples without files.
#pragma once

#include <optional>
#include <string>

#include "compiler/music/tempo_map.hpp"
#include "runtime/audio/audio_files.hpp"
#include "runtime/cli/context.hpp"
#include "runtime/cli/exit_codes.hpp"

namespace seqc::cli {

struct BeatsRequest {
  std::string song;                      // as given: printed in the block's `file:`
  std::optional<music::Meter> meter;     // --meter
  std::optional<double> tempo_hint;      // --tempo-hint, BPM
  std::optional<std::string> click;      // --click OUT.wav
  std::optional<std::string> beats_out;  // --beats-out OUT: music::beat_list
};

// The block on ctx.out, the confidence on ctx.err; FileError when the song cannot be read or the
// click track written, InvalidInput when the song has no steady beat, Usage (before anything is
// read or written) when --click or --beats-out names the song itself.
ExitCode run_beats(Context& ctx, const BeatsRequest& request, audio::AudioReader& reader,
                   audio::AudioWriter& writer);

}  // namespace seqc::cli
