// `seqc plot` and `seqc simulate` for whichever kind of program a file compiles to: a servo
// controller's keyframes or the car's packet stream, as an SVG picture or as positions over
// time (CSV). This is the one place that tells the two kinds apart for them, as a board's
// `render` does for `seqc compile --emit`. No I/O and no words: the CLI writes the result and
// says the summary.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "compiler/compile.hpp"
#include "compiler/formats/plot_svg.hpp"
#include "compiler/formats/preview_html.hpp"
#include "compiler/formats/simulate.hpp"

namespace seqc::boards {

// How long the program runs: when its last move (or packet's effect) ends; 0 without a program.
std::uint64_t length_ms(const compiler::CompileOutput& output);

// The program as a picture (formats/plot_svg); "" without a program.
std::string plot(const compiler::CompileOutput& output, const compiler::PlotOptions& options);

// The song of a file with `music:` as the plot draws it under the lanes: decoded through
// `songs`, with the beats found in it (the file's tempo as the hint between half and double
// readings, its meter given). nullopt without a song or when it cannot be decoded (the check
// has said why); no beats when none are steady enough to find.
std::optional<compiler::PlotSong> plot_song(const compiler::CompileOutput& output,
                                           seqc::SongReader& songs);

// The program as one performer of `seqc preview`'s page (formats/preview_html), on a time axis
// of `end_ms`, with `song` (plot_song) under its lanes when given; nullopt without a program.
std::optional<compiler::PreviewPart> preview_part(const compiler::CompileOutput& output,
                                                 const std::string& title, double end_ms,
                                                 const compiler::PlotSong* song = nullptr);

// The song the preview page embeds and plays: the `music:` file's bytes through `files`, in a
// type a browser plays; nullopt without a song, when it cannot be read or is of another type.
std::optional<compiler::PreviewSong> preview_song(const compiler::CompileOutput& output,
                                                 seqc::FileReader& files);

struct Simulated {
  bool ok = false;  // false: no program of a kind that can be simulated
  std::string csv;  // a sample every step_ms from 0, and the final instant
  std::uint64_t duration_ms = 0;
  std::size_t steps = 0;       // what the program is made of, counted ...
  std::string_view steps_are;  // ... and named: "actions", "packets"
  // With `compare` (servo programs): each servo's largest difference between the compiled
  // motion and the intended curve, and when.
  std::vector<compiler::Difference> differences;
};
Simulated simulate(const compiler::CompileOutput& output, std::uint32_t step_ms, bool compare);

}  // namespace seqc::boards
