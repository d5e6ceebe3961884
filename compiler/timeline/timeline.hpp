// The timeline: what the author meant, per servo, on exact time, before anything is rounded or
// cut into controller actions. The front end adds segments as it walks the steps; fitting
// (compiler/fitting/) turns the whole timeline into the fewest actions that stay within each
// segment's tolerance, and `seqc simulate --compare` reads it as the intended curve.
//
// A servo's segments are in time order and do not overlap. Between segments (and after the
// last) the servo holds its last value; before its first segment its position is unknown.
// A segment is either a hold (the servo is named and re-sent, as by `wait`), a straight line,
// an eased move, or one piece of a C1 cubic Hermite curve (`through`).
//
// Storage is compact, because a group may hold 1,020 steps of 32 servos: what the servos of
// one step share (times, shape, tolerance, source) is kept once, and each servo keeps only its
// own ends and slopes (as floats: well under a thousandth of a unit). segment() rebuilds the
// full Segment.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "base/source.hpp"
#include "compiler/timeline/easing.hpp"
#include "compiler/timeline/exact_time.hpp"
#include "compiler/timeline/song.hpp"
#include "compiler/timeline/tempo_map.hpp"

namespace seqc::compiler {

enum class CurveKind : std::uint8_t { Hold, Linear, Eased, Hermite };

struct Segment {
  Instant start;  // absolute, from the start of the sequence
  Instant end;
  double from = 0;  // device units (not rounded)
  double to = 0;
  CurveKind kind = CurveKind::Linear;
  Easing easing;                        // Eased
  double slope_from = 0, slope_to = 0;  // Hermite: units per millisecond at start and end
  double tolerance = 1;                 // device units, at any instant of this segment
  bool keep_boundaries = false;         // `steps:` pieces: the boundaries are actions, never merged
  // A servo's first move, from a position nobody knows: `from` is its target, and the
  // controller can only be told that end, so the fitter names the servo only in the action that
  // ends with the segment (it holds where it is until then) rather than sending the target in
  // an earlier, shorter action.
  bool from_unknown = false;
  Location at;  // the step (or waypoint) it comes from

  bool is_straight() const { return kind == CurveKind::Hold || kind == CurveKind::Linear; }
  // The intended position at absolute time t (ms), clamped to the segment.
  double value(double t_ms) const;
  // The intended speed at absolute time t (units per ms, signed), from the curve's exact
  // derivative, one-sided at the segment's ends; infinite where the curve is vertical.
  double velocity(double t_ms) const;
};

// The lowest and highest position a segment passes through, its ends included: the true
// extremes of an overshooting ease (back, elastic) or a Hermite piece, found between samples by
// golden-section search, not the values at a few sampled instants. Cost: a fixed number of
// evaluations whatever the segment's length.
struct ValueRange {
  double low = 0;
  double high = 0;
};
ValueRange value_range(const Segment& segment);

// A named moment for plots and listings: a section starting, an `at:` cue, a tempo change.
struct TimelineMarker {
  ExactMs at;
  std::string label;
  Location where;
};

// A warning about a servo at a time (speed, acceleration, fit), for pictures of the timeline.
struct TimelineWarning {
  double at_ms = 0;
  std::size_t servo = 0;
  std::string message;
};

// A move that placed an arm's tip (`move: {tip: ...}`), for pictures of the tip's path: its
// time, where the tip was meant to start and end (mm) and whether it was to go in a straight
// line between them (`path: line`; otherwise the joints' own curves decide the path).
struct TimelineTipMove {
  double start_ms = 0, end_ms = 0;
  std::array<double, 3> from{}, to{};
  bool line = false;
};

class Timeline {
 public:
  void resize(std::size_t servos) { servos_.resize(servos); }
  std::size_t servo_count() const { return servos_.size(); }
  // Appends to `servo`'s segments (after its last one).
  void add(std::size_t servo, const Segment& segment);
  // Puts `with` in place of `servo`'s segments [first, first + count), which it must cover in
  // time as they did: how a `path: line` is fitted again once every track is known.
  void replace(std::size_t servo, std::size_t first, std::size_t count,
               const std::vector<Segment>& with);
  std::size_t count(std::size_t servo) const { return servos_[servo].size(); }
  Segment segment(std::size_t servo, std::size_t i) const;
  Instant start_of(std::size_t servo, std::size_t i) const {
    return spans_[servos_[servo][i].span].start;
  }
  Instant end_of(std::size_t servo, std::size_t i) const {
    return spans_[servos_[servo][i].span].end;
  }
  // The index of the last segment of `servo` starting at or before t, if any.
  std::optional<std::size_t> index_at(std::size_t servo, double t_ms) const;
  // The intended position of `servo` at t, or nullopt while it is still unknown.
  std::optional<double> value(std::size_t servo, double t_ms) const;
  // The position as the file wrote it, for views that compare the motion with it: value(),
  // except where a `path: line` took another servo's curve into its own straight pieces (the
  // fitter works on those; `written` keeps the curve).
  std::optional<double> written_value(std::size_t servo, double t_ms) const {
    const bool taken = servo < taken_into_lines.size() && taken_into_lines[servo];
    return written && taken ? written->value(servo, t_ms) : value(servo, t_ms);
  }
  // The same motion on a clock running num/den as fast: every instant (segments, markers,
  // warnings, the end) multiplied by num/den, Hermite slopes divided by it. An instant of whole
  // milliseconds times whole num and den is computed exactly (the product is below 2^53), so
  // a boundary that lands on a half rounds as the exact value does. The tempo map and song
  // stay as they are (they are the music's, read for pictures).
  Timeline stretched(std::int64_t num, std::int64_t den) const;

  std::vector<TimelineMarker> markers;
  std::vector<TimelineWarning> warnings;
  std::vector<TimelineTipMove> tip_moves;
  ExactMs end;  // when the last step ends
  // Where beats and bars fall (the file's tempo and meter and every change of them), for a
  // beat/bar grid.
  TempoMap tempo_map;
  // The song of the main file's `music:` block, which then owns the tempo map; nullopt without.
  std::optional<Song> song;
  // The timeline before `path: line` fits replaced other servos' curves (see written_value);
  // null when none did. taken_into_lines: by servo, whether a line took its curve.
  std::shared_ptr<const Timeline> written;
  std::vector<bool> taken_into_lines;
  // The audio file the main file's `music:` block names, set also when the block or the steps
  // have mistakes (and song or the fit is then missing): the commands that decode songs still
  // say in the same run whether it can be read.
  std::optional<SongFile> song_file;

 private:
  struct Span {  // what the servos of one step share
    Instant start, end;
    Easing easing;
    float tolerance = 1;
    CurveKind kind = CurveKind::Linear;
    bool keep_boundaries = false;
    Location at;
    bool same(const Segment& s) const;
  };
  struct Piece {  // one servo's own part
    std::uint32_t span = 0;
    float from = 0, to = 0, slope_from = 0, slope_to = 0;
    bool from_unknown = false;
  };
  // The span `s` shares with the servos added just before it (a new one if none).
  std::uint32_t span_for(const Segment& s);
  std::vector<Span> spans_;
  std::vector<std::vector<Piece>> servos_;
};

}  // namespace seqc::compiler
