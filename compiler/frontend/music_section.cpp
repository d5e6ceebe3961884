// parse_music() and the song's tempo map (music_section.hpp).
#include "compiler/frontend/music_section.hpp"

#include <cmath>

#include "base/units.hpp"
#include "compiler/frontend/file_loader.hpp"
#include "compiler/frontend/key_tables.hpp"
#include "compiler/frontend/scope_chain.hpp"

namespace seqc::compiler {
namespace {

std::optional<SongChange> parse_change(const YamlNode& item, Reporter& reporter) {
  if (!item.is_map()) {
    reporter.error(item.location,
                   "a change is a map such as '{bar: 33, tempo: 132}' or '{bar: 49, meter: 3/4}'");
    return std::nullopt;
  }
  bool ok = reporter.check_keys(item, {"bar", "tempo", "meter"}, "in a change of 'music'");
  SongChange change;
  change.at = item.location;
  const YamlNode* bar = item.find("bar");
  double number = 0;
  if (bar == nullptr) {
    reporter.error(item.location,
                   "a change needs the bar it falls on, e.g. '{bar: 33, tempo: 132}'");
    ok = false;
  } else if (!bar->is_scalar() || !parse_decimal(bar->scalar, number) ||
             number != std::floor(number) || number < 2 || number > 1e6) {
    reporter.error(bar->location,
                   "a change falls on a bar line: 'bar' must be a whole bar after bar 1, "
                   "e.g. 'bar: 33'");
    ok = false;
  } else {
    change.bar = static_cast<long long>(number);
    change.at = bar->location;
  }
  if (const YamlNode* t = item.find("tempo")) {
    change.tempo = parse_tempo(*t, reporter);
    ok = ok && change.tempo.has_value();
  }
  if (const YamlNode* m = item.find("meter")) {
    change.meter = parse_meter(*m, reporter);
    ok = ok && change.meter.has_value();
  }
  if (item.find("tempo") == nullptr && item.find("meter") == nullptr) {
    reporter.error(item.location,
                   "a change sets 'tempo', 'meter' or both, e.g. "
                   "'{bar: 33, tempo: 132}'");
    ok = false;
  }
  if (!ok) return std::nullopt;
  return change;
}

}  // namespace

std::optional<Song> parse_music(const YamlNode& key, const YamlNode& music, const std::string& path,
                                Reporter& reporter) {
  if (!music.is_map()) {
    reporter.error(music.is_scalar() ? music.location : key.location,
                   "'music' is a map: the song's 'file', 'downbeat', 'tempo', 'meter' and "
                   "'changes'");
    return std::nullopt;
  }
  bool ok = reporter.check_keys(music, kMusicKeys, "in 'music'");
  Song song;
  song.at = key.location;
  const YamlNode* file = music.find("file");
  if (file == nullptr || !file->is_scalar() || file->scalar.empty()) {
    reporter.error(file != nullptr ? file->location : key.location,
                   "'music' needs the song's audio file, e.g. 'file: song.ogg' (relative to "
                   "this file)");
    ok = false;
  } else {
    song.file = resolve_include(path, file->scalar);
    song.file_at = file->location;
  }
  if (const YamlNode* d = music.find("downbeat")) {
    const Result<TimeValue> t =
        d->is_scalar() ? parse_time(d->scalar) : Result<TimeValue>(make_error(std::string()));
    if (!t || (t->unit != TimeUnit::Milliseconds && t->unit != TimeUnit::Seconds) ||
        t->amount < 0) {
      reporter.error(d->location,
                     "'downbeat' is where bar 1 beat 1 falls in the audio, in "
                     "seconds or milliseconds, e.g. 'downbeat: 0.750s'");
      ok = false;
    } else {
      const ExactMs amount = exact_amount(*t);
      song.downbeat = t->unit == TimeUnit::Seconds ? amount * ExactMs(1000) : amount;
    }
  }
  const YamlNode* tempo = music.find("tempo");
  const YamlNode* meter = music.find("meter");
  if (tempo == nullptr) {
    reporter.error(key.location, "'music' needs the song's 'tempo' (e.g. 'tempo: 128') at bar 1");
    ok = false;
  }
  if (meter == nullptr) {
    reporter.error(key.location, "'music' needs the song's 'meter' (e.g. 'meter: 4/4') at bar 1");
    ok = false;
  }
  if (tempo != nullptr) {
    const std::optional<Tempo> written = parse_tempo(*tempo, reporter);
    ok = ok && written.has_value();
    song.tempo = written.value_or(Tempo{});
  }
  if (meter != nullptr) {
    const std::optional<TimeSignature> written = parse_meter(*meter, reporter);
    ok = ok && written.has_value();
    song.meter = written.value_or(TimeSignature{});
  }
  if (const YamlNode* changes = music.find("changes")) {
    if (!changes->is_sequence()) {
      reporter.error(changes->location,
                     "'changes' is a list such as "
                     "'[{bar: 33, tempo: 132}, {bar: 49, meter: 3/4}]'");
      ok = false;
    } else {
      for (const YamlNode& item : changes->items) {
        std::optional<SongChange> change = parse_change(item, reporter);
        if (!change) {
          ok = false;
          continue;
        }
        if (!song.changes.empty() && change->bar <= song.changes.back().bar) {
          reporter.error(change->at, "the changes go by bar: bar " + std::to_string(change->bar) +
                                         " comes after bar " +
                                         std::to_string(song.changes.back().bar));
          ok = false;
          continue;
        }
        song.changes.push_back(*change);
      }
    }
  }
  if (!ok) return std::nullopt;
  return song;
}

std::optional<SongFile> music_file(const YamlNode& music, const std::string& path) {
  const YamlNode* file = music.is_map() ? music.find("file") : nullptr;
  if (file == nullptr || !file->is_scalar() || file->scalar.empty()) return std::nullopt;
  return SongFile{resolve_include(path, file->scalar), file->location};
}

TempoMap song_tempo_map(const Song& song) {
  TempoMap map(song.tempo, song.meter);
  for (const SongChange& c : song.changes) {
    // The map is exact and every tempo is positive, so each bar line has a time.
    const std::optional<ExactMs> beat = map.beat_of_bar(ExactMs(c.bar - 1));
    const std::optional<ExactMs> at = beat ? map.time_of_beat(*beat) : std::nullopt;
    if (!at) break;
    // The meter first: a tempo beside it counts the new meter's beat, and a meter alone keeps
    // each note's length.
    if (c.meter) map.set_meter(*at, *c.meter);
    if (c.tempo) map.set_tempo(*at, *c.tempo);
  }
  return map;
}

}  // namespace seqc::compiler
