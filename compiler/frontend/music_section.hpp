// The `music:` block of a choreography: the song it dances to, whose tempo map then owns every
// beat and bar of the file. Reading it reports every mistake in the block (unknown keys with
// "did you mean", a downbeat that is not a time, a change not on a whole bar, bars that do not
// increase, a tempo or meter that does not parse); the song's map is built from the result.
#pragma once

#include <optional>
#include <string>

#include "compiler/frontend/reporter.hpp"
#include "compiler/frontend/yaml/yaml_tree.hpp"
#include "compiler/timeline/song.hpp"
#include "compiler/timeline/tempo_map.hpp"

namespace seqc::compiler {

// The song of `music` (the value of the `music` key `key`) in the file at `path`; nullopt after
// reporting.
std::optional<Song> parse_music(const YamlNode& key, const YamlNode& music, const std::string& path,
                                Reporter& reporter);

// The audio file `music` names, when its `file` is a non-empty scalar, whatever else in the block
// is wrong (nothing is reported: parse_music() says the mistakes).
std::optional<SongFile> music_file(const YamlNode& music, const std::string& path);

// The song's tempo map: its tempo and meter at bar 1, then each change at its bar line.
TempoMap song_tempo_map(const Song& song);

}  // namespace seqc::compiler
