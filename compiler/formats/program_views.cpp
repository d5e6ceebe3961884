#include "compiler/formats/program_views.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include "compiler/formats/raspblock_simulate.hpp"
#include "compiler/formats/svg_text.hpp"
#include "compiler/music/beat_analysis.hpp"

namespace seqc::compiler {

std::uint64_t length_ms(const compiler::Program& program) {
  if (const auto* p = std::get_if<compiler::ServoProgram>(&program)) return p->duration_ms();
  if (const auto* p = std::get_if<compiler::RaspblockProgram>(&program)) return p->duration_ms;
  return 0;
}

namespace {

// The song of the file's `music:` block, for every robot kind (the walk keeps it on the
// timeline of both programs).
const compiler::Song* song_of(const compiler::Program& program) {
  const compiler::Timeline& tl =
      std::visit([](const auto& p) -> const compiler::Timeline& { return p.timeline; }, program);
  return tl.song ? &*tl.song : nullptr;
}

}  // namespace

std::optional<PlotSong> plot_song(const compiler::Program& program, seqc::SongReader& songs) {
  const compiler::Song* written = song_of(program);
  if (written == nullptr) return std::nullopt;
  const compiler::Song& song = *written;
  Result<seqc::SongSamples> decoded = songs.read(song.file);
  if (!decoded) return std::nullopt;
  PlotSong out;
  out.label = std::filesystem::path(song.file).filename().string();
  out.sample_rate = decoded->sample_rate;
  out.downbeat_s = song.downbeat.value() / 1000.0;
  music::BeatOptions options;
  options.tempo_hint = song.bpm();
  if (song.meter.beats_per_bar > 0) {
    options.meter = music::Meter{song.meter.beats_per_bar, song.meter.beat_unit};
  }
  if (auto found = music::analyze_beats(decoded->samples, decoded->sample_rate, options)) {
    out.beats_s = std::move(found->beats_s);
  }
  out.samples = std::move(decoded->samples);
  return out;
}

std::string plot_program(const compiler::Program& program, const PlotOptions& options) {
  if (const auto* p = std::get_if<compiler::ServoProgram>(&program)) {
    return plot_servo_program(*p, options);
  }
  if (const auto* p = std::get_if<compiler::RaspblockProgram>(&program)) {
    return plot_car_program(*p, options);
  }
  return "";
}

std::string plot_program(const compiler::Program& program, PlotOptions options,
                         seqc::SongReader* songs) {
  std::optional<PlotSong> song;
  if (songs != nullptr) song = plot_song(program, *songs);
  options.song = song ? &*song : nullptr;
  return plot_program(program, options);
}

const ShowPart* show_song_part(const std::vector<ShowPart>& parts) {
  const ShowPart* first = nullptr;
  for (const ShowPart& p : parts) {
    const compiler::Song* song = song_of(*p.program);
    if (song == nullptr) continue;
    if (first == nullptr) {
      first = &p;
      continue;
    }
    const compiler::Song& one = *song_of(*first->program);
    if (!same_song(*song, one)) return nullptr;
  }
  return first;
}

std::string plot_show(const std::vector<ShowPart>& parts, const std::string& title,
                      const std::string& show, PlotOptions options, seqc::SongReader* songs) {
  // The show's one song, under the lanes of the first performer dancing to it.
  const ShowPart* with_song = songs != nullptr ? show_song_part(parts) : nullptr;
  std::optional<PlotSong> song;
  if (with_song != nullptr) song = plot_song(*with_song->program, *songs);
  double end = 0;
  for (const ShowPart& part : parts) end = std::max(end, double(length_ms(*part.program)));
  if (!options.from_ms) options.from_ms = 0;
  if (!options.to_ms) options.to_ms = end;
  std::string body;
  double y = 36;
  for (const ShowPart& p : parts) {
    options.title = p.title;
    options.song = &p == with_song && song ? &*song : nullptr;
    std::string part = plot_program(*p.program, options);
    const auto h = part.find("height=\"");
    const double height = std::atof(part.c_str() + h + 8);
    part.insert(part.find("<svg") + 4, " y=\"" + std::to_string(static_cast<int>(y)) + "\"");
    body += part;
    y += height + 10;
  }
  return "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"1100\" height=\"" +
         std::to_string(static_cast<int>(y)) + "\" viewBox=\"0 0 1100 " +
         std::to_string(static_cast<int>(y)) + "\" font-family=\"sans-serif\">\n<title>" +
         svg::escape(title) +
         "</title>\n<rect width=\"1100\" "
         "height=\"" +
         std::to_string(static_cast<int>(y)) +
         "\" fill=\"#ffffff\"/>\n<text x=\"12\" "
         "y=\"24\" font-size=\"17\" font-weight=\"bold\">show " +
         svg::escape(show) + " (" + std::to_string(parts.size()) +
         " performers, one clock)</text>\n" + body + "</svg>\n";
}

std::optional<PreviewPart> preview_part(const compiler::Program& program, const std::string& title,
                                        double end_ms, const PlotSong* song) {
  if (const auto* p = std::get_if<compiler::ServoProgram>(&program)) {
    return preview_servo_part(*p, title, end_ms, song);
  }
  if (const auto* p = std::get_if<compiler::RaspblockProgram>(&program)) {
    return preview_car_part(*p, title, end_ms);
  }
  return std::nullopt;
}

std::string preview_show(const std::vector<ShowPart>& parts, const std::string& title,
                         const std::string& show, seqc::SongReader* songs, seqc::FileReader* files,
                         std::string* missing, const std::string& song_url) {
  double end = 0;
  for (const ShowPart& p : parts) end = std::max(end, static_cast<double>(length_ms(*p.program)));
  // The show's one song: played with the page, drawn under the first performer dancing to it.
  const ShowPart* with_song = show_song_part(parts);
  std::optional<PlotSong> picture;
  std::optional<PreviewSong> song;
  if (with_song != nullptr && songs != nullptr) picture = plot_song(*with_song->program, *songs);
  if (with_song != nullptr && files != nullptr) {
    song = preview_song(*with_song->program, *files, songs, song_url);
    if (song && missing != nullptr) *missing = song->missing;
  }
  std::vector<std::string> names;
  std::vector<PreviewPart> drawn;
  for (const ShowPart& p : parts) {
    auto part =
        preview_part(*p.program, p.title, end, &p == with_song && picture ? &*picture : nullptr);
    if (!part) continue;
    names.push_back(p.name);
    drawn.push_back(std::move(*part));
  }
  return preview_page(
      "show " + show + " (" + std::to_string(drawn.size()) + " performers, one clock), " + title,
      names, drawn, end, song ? &*song : nullptr);
}

std::optional<PreviewSong> preview_song(const compiler::Program& program, seqc::FileReader& files,
                                        seqc::SongReader* songs, const std::string& song_url) {
  const compiler::Song* written = song_of(program);
  if (written == nullptr) return std::nullopt;
  const compiler::Song& song = *written;
  const std::string mime = audio_mime(song.file);
  if (mime.empty()) return std::nullopt;
  const double downbeat_s = song.downbeat.value() / 1000.0;
  if (!song_url.empty()) return PreviewSong{"", mime, downbeat_s, "", song_url};
  Result<std::string> bytes = files.read(song.file);
  if (bytes) return PreviewSong{std::move(*bytes), mime, downbeat_s, "", ""};
  std::string why = bytes.error().message;
  if (songs != nullptr) {
    Result<std::string> small = songs->compressed(song.file);
    if (small) return PreviewSong{std::move(*small), "audio/ogg", downbeat_s, "", ""};
    why += "; " + small.error().message;
  }
  return PreviewSong{"", "", downbeat_s,
                     "the song is not in this page (" + why +
                         "): convert it to a smaller file, e.g. `ffmpeg -i " + song.file +
                         " -ac 1 -q:a 3 song.ogg`, and name that in `music: file:`",
                     ""};
}

std::string preview_program(const compiler::Program& program, const std::string& title,
                            seqc::SongReader* songs, seqc::FileReader& files, std::string* missing,
                            const std::string& song_url) {
  const double end = static_cast<double>(length_ms(program));
  std::optional<PlotSong> picture;
  if (songs != nullptr) picture = plot_song(program, *songs);
  const std::optional<PreviewSong> song = preview_song(program, files, songs, song_url);
  if (song && missing != nullptr) *missing = song->missing;
  auto part = preview_part(program, title, end, picture ? &*picture : nullptr);
  if (!part) return "";
  return preview_page(title, {""}, {std::move(*part)}, end, song ? &*song : nullptr);
}

std::uint32_t default_simulate_step_ms(const compiler::Program& program) {
  std::uint64_t duration = 0;
  if (const auto* servo = std::get_if<compiler::ServoProgram>(&program)) {
    duration = servo->duration_ms();
  } else if (const auto* car = std::get_if<compiler::RaspblockProgram>(&program)) {
    duration = car->duration_ms;
  }
  const std::uint64_t step = (duration + kDefaultSimulateRows - 1) / kDefaultSimulateRows;
  return static_cast<std::uint32_t>(std::max<std::uint64_t>(20, step));
}

Simulated simulate(const compiler::Program& program, std::uint32_t step_ms, bool compare) {
  Simulated out;
  if (const auto* servo = std::get_if<compiler::ServoProgram>(&program)) {
    const Simulation sim = simulate(*servo, step_ms, compare);
    if (compare) out.differences = compare_with_intent(*servo);
    out.csv = to_csv(sim);
    out.duration_ms = sim.duration_ms;
    out.steps = servo->keyframes.size();
    out.steps_are = "actions";
    out.ok = true;
  } else if (const auto* car = std::get_if<compiler::RaspblockProgram>(&program)) {
    const CarSimulation sim = simulate_car(*car, step_ms);
    out.csv = to_csv(sim);
    out.duration_ms = sim.duration_ms;
    out.steps = car->packets.size();
    out.steps_are = "packets";
    out.ok = true;
  }
  return out;
}

}  // namespace seqc::compiler
