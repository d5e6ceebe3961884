#include "compiler/timeline/tempo_map.hpp"

namespace seqc::compiler {
namespace {

ExactMs ms_per_beat(double bpm) {
  return bpm > 0 ? ExactMs(60000) / ExactMs::from_double(bpm) : ExactMs(0);
}

}  // namespace

ExactMs beat_ms(const Tempo& tempo, int beat_unit) {
  if (tempo.per_minute <= 0) return ExactMs(0);
  const ExactMs note = ms_per_beat(tempo.per_minute);
  if (tempo.note_num <= 0 || tempo.note_den <= 0) return note;
  // A note of num/den of a whole lasts `note`, so a whole lasts note * den / num and a beat
  // (1/beat_unit of a whole) that divided by beat_unit.
  return note * ExactMs(tempo.note_den) / ExactMs(tempo.note_num * beat_unit);
}

ExactMs exact_amount(const TimeValue& t) {
  if (t.denominator > 0) return ExactMs::ratio(t.numerator, t.denominator);
  return ExactMs::from_double(t.amount);
}

TempoMap::TempoMap(double bpm, int beats_per_bar, int beat_unit) {
  Change start;
  start.bpm = bpm;
  start.ms_per_beat = ms_per_beat(bpm);
  start.beats_per_bar = beats_per_bar;
  start.beat_unit = beat_unit;
  changes_.push_back(start);
}

TempoMap::TempoMap(const Tempo& tempo, const TimeSignature& meter)
    : TempoMap(tempo.per_minute, meter.beats_per_bar, meter.beat_unit) {
  if (tempo.note_num > 0) set_beat_ms(ExactMs(0), beat_ms(tempo, meter.beat_unit));
}

const TempoMap::Change& TempoMap::in_force(ExactMs t) const {
  for (auto it = changes_.rbegin(); it != changes_.rend(); ++it) {
    if (it->at <= t) return *it;
  }
  return changes_.front();
}

TempoMap::Change& TempoMap::change_at(ExactMs at) {
  if (at <= changes_.back().at) return changes_.back();
  Change next = changes_.back();
  next.beat = beat_at(at);
  next.bar = bar_of_beat(next.beat);
  next.at = at;
  changes_.push_back(next);
  return changes_.back();
}

void TempoMap::set_tempo(ExactMs at, double bpm) {
  if (bpm_at(at) == bpm) return;
  Change& c = change_at(at);
  c.bpm = bpm;
  c.ms_per_beat = ms_per_beat(bpm);
}

void TempoMap::set_tempo(ExactMs at, const Tempo& tempo) {
  if (tempo.note_num <= 0) {
    set_tempo(at, tempo.per_minute);
    return;
  }
  set_beat_ms(at, beat_ms(tempo, beat_unit_at(at)));
}

void TempoMap::set_beat_ms(ExactMs at, ExactMs ms_per_beat) {
  if (in_force(at).ms_per_beat == ms_per_beat) return;
  Change& c = change_at(at);
  c.ms_per_beat = ms_per_beat;
  c.bpm = ms_per_beat > ExactMs(0) ? (ExactMs(60000) / ms_per_beat).value() : 0;
}

void TempoMap::set_meter(ExactMs at, int beats_per_bar, int beat_unit) {
  const Change& now = in_force(at);
  if (now.beats_per_bar == beats_per_bar && now.beat_unit == beat_unit) return;
  Change& c = change_at(at);
  if (c.beat_unit != beat_unit && c.bpm > 0) {
    // Each note keeps its length: a beat half as long comes twice as often.
    c.ms_per_beat = c.ms_per_beat * ExactMs(c.beat_unit) / ExactMs(beat_unit);
    c.bpm = c.bpm * beat_unit / c.beat_unit;
  }
  c.beats_per_bar = beats_per_bar;
  c.beat_unit = beat_unit;
}

ExactMs TempoMap::beat_at(ExactMs t) const {
  const Change& c = in_force(t);
  if (c.bpm <= 0) return c.beat;
  return c.beat + (t - c.at) / c.ms_per_beat;
}

ExactMs TempoMap::bar_of_beat(ExactMs beat) const {
  for (auto it = changes_.rbegin(); it != changes_.rend(); ++it) {
    if (it->beat > beat) continue;
    if (it->beats_per_bar <= 0) return it->bar;
    return it->bar + (beat - it->beat) / ExactMs(it->beats_per_bar);
  }
  return ExactMs(0);
}

std::optional<ExactMs> TempoMap::time_of_beat(ExactMs beat) const {
  for (auto it = changes_.rbegin(); it != changes_.rend(); ++it) {
    if (it->beat > beat) continue;
    if (it->bpm > 0) return it->at + (beat - it->beat) * it->ms_per_beat;
    if (it->beat == beat) return it->at;
    return std::nullopt;
  }
  return std::nullopt;
}

std::optional<ExactMs> TempoMap::beat_of_bar(ExactMs bar) const {
  for (auto it = changes_.rbegin(); it != changes_.rend(); ++it) {
    if (it->bar > bar) continue;
    if (it->beats_per_bar > 0) return it->beat + (bar - it->bar) * ExactMs(it->beats_per_bar);
    if (it->bar == bar) return it->beat;
    return std::nullopt;
  }
  return std::nullopt;
}

std::optional<ExactMs> TempoMap::after_beats(ExactMs t, ExactMs beats) const {
  if (beats == ExactMs(0)) return t;
  std::size_t i = changes_.size() - 1;
  while (i > 0 && changes_[i].at > t) --i;
  ExactMs now = t;
  ExactMs left = beats;
  for (; i < changes_.size(); ++i) {
    const Change& c = changes_[i];
    if (c.bpm <= 0) return std::nullopt;
    const ExactMs end = now + left * c.ms_per_beat;
    if (i + 1 == changes_.size() || end <= changes_[i + 1].at) return end;
    left = left - (changes_[i + 1].at - now) / c.ms_per_beat;
    now = changes_[i + 1].at;
  }
  return std::nullopt;
}

std::optional<ExactMs> TempoMap::after_bars(ExactMs t, ExactMs bars) const {
  std::size_t i = changes_.size() - 1;
  while (i > 0 && changes_[i].at > t) --i;
  const ExactMs from = beat_at(t);
  ExactMs beat = from;
  ExactMs left = bars;
  for (; i < changes_.size(); ++i) {
    const Change& c = changes_[i];
    if (c.beats_per_bar <= 0) return std::nullopt;
    const ExactMs per_bar(c.beats_per_bar);
    const ExactMs end = beat + left * per_bar;
    if (i + 1 == changes_.size() || end <= changes_[i + 1].beat) {
      beat = end;
      break;
    }
    left = left - (changes_[i + 1].beat - beat) / per_bar;
    beat = changes_[i + 1].beat;
  }
  return after_beats(t, beat - from);
}

std::optional<ExactMs> TempoMap::after(ExactMs t, ExactMs amount, TimeUnit unit) const {
  switch (unit) {
    case TimeUnit::Milliseconds:
      return t + amount;
    case TimeUnit::Seconds:
      return t + amount * ExactMs(1000);
    case TimeUnit::Beats:
      return after_beats(t, amount);
    case TimeUnit::Bars:
      return after_bars(t, amount);
  }
  return std::nullopt;
}

std::optional<ExactMs> TempoMap::time_of_bar(ExactMs bar) const {
  return time_of_bar_beat(bar, ExactMs(0));
}

std::optional<ExactMs> TempoMap::time_of_bar_beat(ExactMs bar, ExactMs beat) const {
  const std::optional<ExactMs> first = beat_of_bar(bar);
  if (!first) return std::nullopt;
  return time_of_beat(*first + beat);
}

std::optional<TempoMap::BarOffset> TempoMap::off_bar_line(ExactMs t) const {
  const ExactMs bar = bar_at(t);
  if (bar.den() == 1) return std::nullopt;
  const std::int64_t whole = bar.num() / bar.den();  // bars are never negative
  return BarOffset{whole, beat_at(t) - beat_of_bar(whole).value_or(ExactMs(0))};
}

}  // namespace seqc::compiler
