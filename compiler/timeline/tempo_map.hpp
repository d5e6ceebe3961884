// The tempo map: how beats and bars fall on the sequence's exact clock. It is the file's tempo
// and meter at the start, then every tempo and meter change in time order, so a time written in
// beats or bars means the same thing to the front end (durations, `at:` offsets and
// `at: bar N beat B` positions) and to pictures of the timeline (the plot's beat grid and bar
// numbers).
//
// Everything is exact: beats and bars are counted in the same rational type as milliseconds
// (ExactMs), so a beat at 110 bpm is 6000/11 ms and bar 9 lands on the same instant however the
// tempo changed before it.
//
// A beat is the note value the meter's lower number names (a quarter in 3/4, an eighth in 6/8;
// a quarter where no meter is set), and a tempo counts those beats. A meter change keeps every
// note value's length, as a score, a DAW and MIDI do: 3/4 at 90 bpm then 6/8 makes the eighth
// 180 bpm, so both bars last 2 s. A tempo given with its own note ("dotted quarter = 60") is
// turned into beats of the meter in force when it is set.
//
// Where no tempo is set the beat clock stands still (no beat passes);
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

// A tempo as written: `per_minute` notes a minute, each note `note_num`/`note_den` of a whole
// note (3/8 for a dotted quarter); a note of 0/0 counts the beat of the meter in force.
struct Tempo {
  double per_minute = 0;
  std::int64_t note_num = 0;
  std::int64_t note_den = 0;
  friend bool operator==(const Tempo&, const Tempo&) = default;
};

// A meter as written, 6/8: beats a bar over the note value of a beat.
struct TimeSignature {
  int beats_per_bar = 0;
  int beat_unit = 4;
  friend bool operator==(const TimeSignature&, const TimeSignature&) = default;
};

// How long a beat lasts at `tempo` where a beat is a 1/`beat_unit` note; 0 for no tempo.
ExactMs beat_ms(const Tempo& tempo, int beat_unit);

// The amount of a written time, exact: a fraction as written (1/3), a decimal to 1e-6.
ExactMs exact_amount(const TimeValue& t);

class TempoMap {
 public:
  struct Change {
    ExactMs at;             // when, from the start of the sequence
    ExactMs beat;           // beats counted from the start until `at`
    ExactMs bar;            // bars counted from the start until `at`
    double bpm = 0;         // 0: no tempo from here
    ExactMs ms_per_beat;    // 60000 / bpm, exact (0 when no tempo)
    int beats_per_bar = 0;  // 0: no meter from here
    int beat_unit = 4;      // the note value a beat counts: 4 a quarter, 8 an eighth
  };

  TempoMap() { changes_.push_back({}); }
  // The tempo and meter in force at the start (0: none); `bpm` counts 1/`beat_unit` notes.
  TempoMap(double bpm, int beats_per_bar, int beat_unit = 4);
  TempoMap(const Tempo& tempo, const TimeSignature& meter);

  // From `at` (no earlier than the last change) on: `bpm` beats of the meter in force a minute,
  // `tempo` as written, or a beat of `ms_per_beat`.
  void set_tempo(ExactMs at, double bpm);
  void set_tempo(ExactMs at, const Tempo& tempo);
  void set_beat_ms(ExactMs at, ExactMs ms_per_beat);
  // From `at` on, `beats_per_bar` beats of 1/`beat_unit` notes a bar; a note keeps its length,
  // so a new beat unit changes the beats a minute.
  void set_meter(ExactMs at, int beats_per_bar, int beat_unit = 4);
  void set_meter(ExactMs at, const TimeSignature& meter) {
    set_meter(at, meter.beats_per_bar, meter.beat_unit);
  }

  double bpm_at(ExactMs t) const { return in_force(t).bpm; }
  ExactMs beat_ms_at(ExactMs t) const { return in_force(t).ms_per_beat; }
  int meter_at(ExactMs t) const { return in_force(t).beats_per_bar; }
  int beat_unit_at(ExactMs t) const { return in_force(t).beat_unit; }
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
