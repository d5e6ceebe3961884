// `seqc plot`, `seqc simulate` and `seqc preview`'s performers for whichever kind of program a
// file compiles to: a servo controller's keyframes or the car's packet stream, as an SVG
// picture, as positions over time (CSV) or as a part of the preview page. This is the one place
// that tells the two kinds apart for them, as a board's `render` does for `seqc compile --emit`,
// so the commands never ask which kind a program is. No words: the CLI writes the result and
// says the summary.
//
// The song of a `music:` block is the only input besides the program, and it comes through the
// caller's readers (base/source.hpp): plot_song() decodes the audio through a SongReader (in
// seqc, libsndfile behind runtime/audio's AudioReader) and finds its beats (compiler/music);
// preview_song() reads the file's bytes through a FileReader. Nothing here opens a file itself.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/source.hpp"
#include "compiler/formats/plot_svg.hpp"
#include "compiler/formats/preview_html.hpp"
#include "compiler/formats/simulate.hpp"
#include "compiler/program/program.hpp"

namespace seqc::compiler {

// How long the program runs: when its last move (or packet's effect) ends.
std::uint64_t length_ms(const compiler::Program& program);

// The program as a picture (plot_svg); "" for a kind it cannot draw.
std::string plot_program(const compiler::Program& program, const PlotOptions& options);
// A single file's picture: the same with its song under the lanes (plot_song through `songs`,
// when given) in place of options.song.
std::string plot_program(const compiler::Program& program, PlotOptions options,
                         seqc::SongReader* songs);

// One performer of a show's picture or page: its program, the title its part is drawn under and
// (for the page's `seqc-state`) its name.
struct ShowPart {
  const compiler::Program* program = nullptr;
  std::string title;
  std::string name;
};

// A show's picture: every part's plot_program() on one time axis (options.from_ms and to_ms,
// by default 0 and the longest part's end), stacked as nested <svg> elements in one document
// whose <title> is `title` and whose heading names the show `show` and counts its parts.
// The show's one song (shown under the first performer whose file has it) comes through `songs`
// when given.
std::string plot_show(const std::vector<ShowPart>& parts, const std::string& title,
                      const std::string& show, PlotOptions options,
                      seqc::SongReader* songs = nullptr);

// The part whose `music:` song is the show's one song: the first with a song, when every part
// with one names the same file and downbeat (as `seqc show --music` plays it); else nullptr.
const ShowPart* show_song_part(const std::vector<ShowPart>& parts);

// The song of a file with `music:` as the plot draws it under the lanes: decoded through
// `songs`, with the beats found in it (the file's tempo as the hint between half and double
// readings, its meter given). nullopt without a song or when it cannot be decoded (the check
// has said why); no beats when none are steady enough to find.
std::optional<PlotSong> plot_song(const compiler::Program& program, seqc::SongReader& songs);

// The program as one performer of `seqc preview`'s page (preview_html), on a time axis of
// `end_ms`, with `song` (plot_song) under its lanes when given; nullopt for a kind it cannot
// show.
std::optional<PreviewPart> preview_part(const compiler::Program& program, const std::string& title,
                                        double end_ms, const PlotSong* song = nullptr);

// A show's page (preview_page): every part it can draw (preview_part) on one time axis, the
// longest part's, titled "show SHOW (N performers, one clock), TITLE" where N counts those parts.
// The show's one song (show_song_part) is embedded to play through `files` and drawn under its
// performer's lanes through `songs`, when given.
// `missing`, when given, gets the song's PreviewSong::missing (for the command to warn).
// `song_url`, when not empty, is where the page fetches the song instead (preview_song).
std::string preview_show(const std::vector<ShowPart>& parts, const std::string& title,
                         const std::string& show, seqc::SongReader* songs = nullptr,
                         seqc::FileReader* files = nullptr, std::string* missing = nullptr,
                         const std::string& song_url = "");

// The song the preview page embeds and plays: the `music:` file's bytes through `files`, in a
// type a browser plays; when `files` refuses them (a song over its size limit, which it checks
// before reading) the song re-encoded small through `songs` (SongReader::compressed); when that
// fails too, a song whose `missing` says why and how to fix it. nullopt without a song, or for
// a type a browser may not play. With `song_url` the page fetches the song from there (the
// studio's server): nothing is read, and the song has that url and no bytes.
std::optional<PreviewSong> preview_song(const compiler::Program& program, seqc::FileReader& files,
                                        seqc::SongReader* songs = nullptr,
                                        const std::string& song_url = "");

// A single file's page (preview_page): its one part on its own time axis, titled `title`, with
// its song drawn under the lanes (plot_song through `songs`, when given) and embedded to play
// (preview_song through `files`); "" for a kind it cannot show.
std::string preview_program(const compiler::Program& program, const std::string& title,
                            seqc::SongReader* songs, seqc::FileReader& files,
                            std::string* missing = nullptr, const std::string& song_url = "");

struct Simulated {
  bool ok = false;  // false: a kind of program that cannot be simulated
  std::string csv;  // a sample every step_ms from 0, and the final instant
  std::uint64_t duration_ms = 0;
  std::size_t steps = 0;       // what the program is made of, counted ...
  std::string_view steps_are;  // ... and named: "actions", "packets"
  // With `compare` (servo programs): each servo's largest difference between the compiled
  // motion and the intended curve, and when.
  std::vector<Difference> differences;
};
Simulated simulate(const compiler::Program& program, std::uint32_t step_ms, bool compare);

// `seqc simulate`'s step without --step: 20 ms, or the whole milliseconds that keep a long
// program to kDefaultSimulateRows rows, so that its output grows no further with its length.
constexpr std::uint64_t kDefaultSimulateRows = 50'000;
std::uint32_t default_simulate_step_ms(const compiler::Program& program);

}  // namespace seqc::compiler
