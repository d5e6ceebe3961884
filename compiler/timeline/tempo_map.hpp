// The tempo map: how beats and bars fall on the sequence's exact clock. It is the file's tempo
// and meter at the start, then every tempo and meter change in time order, so a time written in
// beats or bars means the same thing to the front end (durations, `at:` offsets and
// `at: bar N beat B` positions) and to pictures of the timeline (the plot's beat grid and bar
// numbers).
//
// Everything is exact: beats and bars are counted in the same rational type as milliseconds
// (ExactMs), so a beat at 110 bpm is 6000/11 ms and bar 9 lands on the same instant however the
// tempo changed before it. Where no tempo is set the beat clock stands still (no beat passes);
// where no meter is set the bar clock does. Bar and beat counts start at 0 here: "bar 1 beat 1"
// of a musician is beat 0, the start of the sequence.
//
// All the musical-time arithmetic is here, none of the wording: a time written in any unit
// after an instant, where a bar and a beat in it fall, and how far an instant is off its bar
// line. An answer the map cannot give is nullopt; the front end says why in the words of the
// language.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "base/units.hpp"
#include "compiler/timeline/exact_time.hpp"

namespace seqc::compiler {

class TempoMap {
 public:
  struct Change {
    ExactMs at;             // when, from the start of the sequence
    ExactMs beat;           // beats counted from the start until `at`
    ExactMs bar;            // bars counted from the start until `at`
    double bpm = 0;         // 0: no tempo from here
    ExactMs ms_per_beat;    // 60000 / bpm, exact (0 when no tempo)
    int beats_per_bar = 0;  // 0: no meter from here
  };

  TempoMap() { changes_.push_back({}); }
  // The tempo and meter in force at the start (0: none).
  TempoMap(double bpm, int beats_per_bar);

  // From `at` (no earlier than the last change) on, `bpm` beats per minute / `beats_per_bar`.
  void set_tempo(ExactMs at, double bpm);
  void set_meter(ExactMs at, int beats_per_bar);

  double bpm_at(ExactMs t) const { return in_force(t).bpm; }
  int meter_at(ExactMs t) const { return in_force(t).beats_per_bar; }
  // Beats (bars) counted from the start of the sequence until `t`.
  ExactMs beat_at(ExactMs t) const;
  ExactMs bar_at(ExactMs t) const { return bar_of_beat(beat_at(t)); }
  ExactMs bar_of_beat(ExactMs beat) const;
  // When beat `beat` (counted from 0) falls; nullopt where the beat clock stands still for good.
  std::optional<ExactMs> time_of_beat(ExactMs beat) const;
  // The beat on which bar `bar` (counted from 0) starts; nullopt where no meter counts it.
  std::optional<ExactMs> beat_of_bar(ExactMs bar) const;
  // `t` plus `beats` beats (bars), counted piecewise through every change on the way; nullopt
  // when no tempo (meter) is in force at `t` or somewhere on the way.
  std::optional<ExactMs> after_beats(ExactMs t, ExactMs beats) const;
  std::optional<ExactMs> after_bars(ExactMs t, ExactMs bars) const;
  // `t` plus `amount` of `unit`: milliseconds and seconds as they are, beats and bars as
  // after_beats and after_bars count them.
  std::optional<ExactMs> after(ExactMs t, ExactMs amount, TimeUnit unit) const;

  // When bar `bar` starts, and when beat `beat` of it falls (both counted from 0: a musician's
  // "bar 9 beat 3" is bar 8, beat 2); nullopt where no meter counts up to the bar or no tempo
  // up to the beat. A beat past the bar's end falls in the bars after it: whether the bar has
  // that beat is meter_at(time_of_bar(bar)).
  std::optional<ExactMs> time_of_bar(ExactMs bar) const;
  std::optional<ExactMs> time_of_bar_beat(ExactMs bar, ExactMs beat) const;

  // An instant inside a bar: the bar (counted from 0) and the beats since it started.
  struct BarOffset {
    std::int64_t bar = 0;
    ExactMs beats;
  };
  // Where `t` falls in its bar; nullopt when it is on a bar line (also where the bar clock has
  // stood still since one).
  std::optional<BarOffset> off_bar_line(ExactMs t) const;

  const std::vector<Change>& changes() const { return changes_; }

 private:
  const Change& in_force(ExactMs t) const;
  // The change to alter for a change at `at`: the last one when it is at `at`, else a new one.
  Change& change_at(ExactMs at);

  std::vector<Change> changes_;  // in time order; the first is at 0
};

}  // namespace seqc::compiler
