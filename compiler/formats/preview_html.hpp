// `seqc preview`: a program (or a show's performers, on one clock) as ONE self-contained HTML
// page that animates it: no network, no external script, font or image; inline CSS, script and
// SVG only, so it opens from disk in any current browser.
//
// Each performer is a part: its lanes (the `seqc plot` picture: the curve as written dashed, the
// controller's motion solid, the bar/beat ruler, sections, cues, warnings) with a playhead, and
// its robot, animated: an arm with geometry from the side and from above with its claw; a board
// without geometry as a row of dials, one per servo; the car from above on its path with the
// gimbal's heading. The page plays, pauses, scrubs (click or drag on the lanes or the slider),
// loops a range of bars and plays at 1/2 and 1/4 speed, all from one time source, `clock()`
// (seconds). A file with `music:` brings its song: the audio is embedded in the page (a data:
// URL, so nothing is fetched), its waveform and beats are drawn under the lanes, and then the
// <audio> element (id `song`) IS the time source: the sequence's time is the audio's
// currentTime minus the downbeat, so the picture follows the audio's clock, not a timer, and
// seeking, pausing or changing the rate of the page does the same to the audio. Past the
// audio's end the page goes on on the wall clock.
//
// The page's fixed text lives as ordinary files in formats/preview/ (preview.html, preview.css
// and the script's files), embedded at build time (preview_page_text.hpp); this file fills in
// the title, the data, the lanes and the song. The script mirrors two pieces of the compiler
// exactly: the controller's motion of formats/simulate.cpp in preview/motion.js and the forward
// kinematics of program/arm_kinematics.hpp in preview/kinematics.js.
//
// The page's contract, which tests and screenshots rely on:
//   - `#t=SECONDS` in the URL shows that instant, paused;
//   - the element `seqc-state` holds JSON for the instant shown:
//       {"t": seconds, "servos": {"name": position, ...}, "tip": [x, y, z]}
//     ("tip" in mm, arms with geometry only; a car has "car": {"x": mm, "y": mm, "heading":
//     degrees clockwise from its start}); a show's is {"t": seconds, "performers": {"name":
//     {...}, ...}} with one such object (without "t") per performer;
//   - servo positions are the controller's motion: straight lines between the compiled actions,
//     interpolated in the page exactly as formats/simulate.cpp does, to two decimals;
//   - the first performer's side view of an arm is a 400 x 400 px SVG whose top-left corner is
//     at page pixel (8, 80), 0.4 px per mm, r = 0 at x = 200 and z = 0 at y = 300 inside it; the
//     tip is a dot of colour #ff00ff, the only one of that colour on the page.
#pragma once

#include <string>
#include <vector>

#include "compiler/formats/plot_song.hpp"
#include "compiler/program/program.hpp"
#include "compiler/program/raspblock_program.hpp"

namespace seqc::compiler {

// One performer of the page: what its script reads and its lanes picture.
struct PreviewPart {
  std::string data_json;
  std::string lanes_svg;
};

// The song the page plays: the audio file's bytes (as they are on disk, or re-encoded when too
// large to embed as they are), its MIME type (audio_mime) and where the sequence's time 0 falls
// in it. When it could not be embedded, `missing` says why and how to fix it, and the page says
// that where the player would be.
struct PreviewSong {
  std::string bytes;
  std::string mime;
  double downbeat_s = 0;
  std::string missing;
  // Set when the page fetches the song from this address instead of holding its bytes (the
  // studio's page, served with the song beside it by `seqc studio`); `bytes` is then unused.
  std::string url;
};

// The type a browser needs for an audio file, by its extension (.wav audio/wav, .flac
// audio/flac, .ogg and .opus audio/ogg, .mp3 audio/mpeg); "" for any other.
std::string audio_mime(const std::string& path);

// `title` names the part; `end_ms` is the page's time axis (a show's longest performer);
// `song`, when given, is drawn under the lanes as `seqc plot` draws it.
PreviewPart preview_servo_part(const compiler::ServoProgram& program, const std::string& title,
                               double end_ms, const PlotSong* song = nullptr);
PreviewPart preview_car_part(const compiler::RaspblockProgram& program, const std::string& title,
                             double end_ms);

// The whole page. `names` (one per part) label a show's performers in `seqc-state`; a single
// file passes one part and an empty name.
std::string preview_page(const std::string& title, const std::vector<std::string>& names,
                         const std::vector<PreviewPart>& parts, double end_ms,
                         const PreviewSong* song = nullptr);

}  // namespace seqc::compiler
