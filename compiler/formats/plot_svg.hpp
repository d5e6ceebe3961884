// `seqc plot`: a program as a self-contained SVG picture (no scripts, no external fonts or
// files), for people who would rather look than read.
//
// Servo controller: one lane per servo the program moves, labelled with its name and unit; the
// intended curve (dashed) and the compiled motion (solid) on the same axes, so where fitting
// departs from the curve it shows; the servo's limits as shaded bands; a tick per action that
// moves it; the beat and bar grid when the file has a tempo (bar numbers on the axis);
// sections, `at:` cues and tempo changes as labelled markers; every warning (speed,
// acceleration, fit) as a marker at its time whose <title> is the message. With a song, its
// waveform and the beats found in it in a lane under the servos, the bar grid over it. When the
// file placed an arm's tip (Timeline::tip_moves), two panels of the tip's path in mm below the
// lanes, from above and from the side, with each `path: line` move's intended line dashed.
//
// Raspblock: the gimbal and servo outputs over time on the same time axis, each lane with its
// values (500, 1500, 2500 us), under the same bar grid and markers; and the car's path seen from
// above, integrating the rocker speeds (the model is printed on the picture), with a scale bar
// in its nominal centimetres.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "compiler/formats/plot_song.hpp"
#include "compiler/program/program.hpp"
#include "compiler/program/raspblock_program.hpp"

namespace seqc::compiler {

struct PlotOptions {
  std::string title;               // e.g. the file name
  const PlotSong* song = nullptr;  // the `music:` song, drawn under the lanes (plot_song.hpp)
  std::optional<double> from_ms;   // the time window (default: the whole program)
  std::optional<double> to_ms;
};

std::string plot_servo_program(const compiler::ServoProgram& program, const PlotOptions& options);
std::string plot_car_program(const compiler::RaspblockProgram& program, const PlotOptions& options);

}  // namespace seqc::compiler
