#include "runtime/boards/program_views.hpp"

#include <filesystem>

#include "compiler/music/beat_analysis.hpp"

#include "compiler/formats/raspblock_simulate.hpp"

namespace seqc::boards {

std::uint64_t length_ms(const compiler::CompileOutput& output) {
  if (const compiler::ServoProgram* p = output.servo_program()) return p->duration_ms();
  if (const compiler::RaspblockProgram* p = output.raspblock_program()) return p->duration_ms;
  return 0;
}

std::optional<compiler::PlotSong> plot_song(const compiler::CompileOutput& output,
                                           seqc::SongReader& songs) {
  const compiler::ServoProgram* program = output.servo_program();
  if (program == nullptr || !program->timeline.song) return std::nullopt;
  const compiler::Song& song = *program->timeline.song;
  Result<seqc::SongSamples> decoded = songs.read(song.file);
  if (!decoded) return std::nullopt;
  compiler::PlotSong out;
  out.label = std::filesystem::path(song.file).filename().string();
  out.sample_rate = decoded->sample_rate;
  out.downbeat_s = song.downbeat.value() / 1000.0;
  music::BeatOptions options;
  options.tempo_hint = song.bpm;
  if (song.beats_per_bar > 0) options.meter = music::Meter{song.beats_per_bar, 4};
  if (auto found = music::analyze_beats(decoded->samples, decoded->sample_rate, options)) {
    out.beats_s = std::move(found->beats_s);
  }
  out.samples = std::move(decoded->samples);
  return out;
}

std::string plot(const compiler::CompileOutput& output, const compiler::PlotOptions& options) {
  if (const compiler::ServoProgram* p = output.servo_program()) {
    return compiler::plot_servo_program(*p, options);
  }
  if (const compiler::RaspblockProgram* p = output.raspblock_program()) {
    return compiler::plot_car_program(*p, options);
  }
  return "";
}

std::optional<compiler::PreviewPart> preview_part(const compiler::CompileOutput& output,
                                                 const std::string& title, double end_ms,
                                                 const compiler::PlotSong* song) {
  if (const compiler::ServoProgram* p = output.servo_program()) {
    return compiler::preview_servo_part(*p, title, end_ms, song);
  }
  if (const compiler::RaspblockProgram* p = output.raspblock_program()) {
    return compiler::preview_car_part(*p, title, end_ms);
  }
  return std::nullopt;
}

std::optional<compiler::PreviewSong> preview_song(const compiler::CompileOutput& output,
                                                 seqc::FileReader& files) {
  const compiler::ServoProgram* program = output.servo_program();
  if (program == nullptr || !program->timeline.song) return std::nullopt;
  const compiler::Song& song = *program->timeline.song;
  const std::string mime = compiler::audio_mime(song.file);
  if (mime.empty()) return std::nullopt;
  Result<std::string> bytes = files.read(song.file);
  if (!bytes) return std::nullopt;
  return compiler::PreviewSong{std::move(*bytes), mime, song.downbeat.value() / 1000.0};
}

Simulated simulate(const compiler::CompileOutput& output, std::uint32_t step_ms, bool compare) {
  Simulated out;
  if (const compiler::ServoProgram* program = output.servo_program()) {
    const compiler::Simulation sim = compiler::simulate(*program, step_ms, compare);
    if (compare) out.differences = compiler::compare_with_intent(*program);
    out.csv = compiler::to_csv(sim);
    out.duration_ms = sim.duration_ms;
    out.steps = program->keyframes.size();
    out.steps_are = "actions";
    out.ok = true;
  } else if (const compiler::RaspblockProgram* car = output.raspblock_program()) {
    const compiler::CarSimulation sim = compiler::simulate_car(*car, step_ms);
    out.csv = compiler::to_csv(sim);
    out.duration_ms = sim.duration_ms;
    out.steps = car->packets.size();
    out.steps_are = "packets";
    out.ok = true;
  }
  return out;
}

}  // namespace seqc::boards
