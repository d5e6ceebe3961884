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
// (seconds), which an <audio> element can later drive.
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

#include "compiler/program/program.hpp"
#include "compiler/program/raspblock_program.hpp"

namespace seqc::backend {

// One performer of the page: what its script reads and its lanes picture.
struct PreviewPart {
  std::string data_json;
  std::string lanes_svg;
};

// `title` names the part; `end_ms` is the page's time axis (a show's longest performer).
PreviewPart preview_servo_part(const compiler::ServoProgram& program, const std::string& title,
                               double end_ms);
PreviewPart preview_car_part(const compiler::RaspblockProgram& program, const std::string& title,
                             double end_ms);

// The whole page. `names` (one per part) label a show's performers in `seqc-state`; a single
// file passes one part and an empty name.
std::string preview_page(const std::string& title, const std::vector<std::string>& names,
                         const std::vector<PreviewPart>& parts, double end_ms);

// The page's script and style (preview_script.cpp).
const std::string& preview_script();
const std::string& preview_style();

}  // namespace seqc::backend
