// seqc beats SONG [--meter N/D] [--tempo-hint BPM] [--click OUT.wav] [--beats-out OUT]: the
// song's beats as a `music:` block (compiler/music), decoded by libsndfile (runtime/audio).
#include <cstdio>
#include <memory>

#include <CLI/CLI.hpp>

#include "compiler/music/beat_analysis.hpp"
#include "compiler/music/click_track.hpp"
#include "runtime/audio/sndfile_audio.hpp"
#include "runtime/cli/beats_command.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/compile_report.hpp"

namespace seqc::cli {

ExitCode run_beats(Context& ctx, const BeatsRequest& request, audio::AudioReader& reader,
                   audio::AudioWriter& writer) {
  for (const auto& [option, path] :
       {std::pair{"--click", request.click}, std::pair{"--beats-out", request.beats_out}}) {
    if (path && refuse_input_as_output(ctx, option, *path, {request.song})) return ExitCode::Usage;
  }
  auto song = reader.read(request.song);
  if (!song) return fail(ctx, ExitCode::FileError, song.error().message);
  music::BeatOptions options;
  options.meter = request.meter;
  options.tempo_hint = request.tempo_hint;
  auto analysis = music::analyze_beats(song->samples, song->sample_rate, options);
  if (!analysis) {
    return fail(ctx, ExitCode::InvalidInput, request.song + ": " + analysis.error().message);
  }
  ctx.out << music::music_block(request.song, analysis->map);
  summarize(ctx, request.song + ": " + music::analysis_summary(*analysis));
  if (request.beats_out) {
    const ExitCode code = write_output(ctx, *request.beats_out, music::beat_list(*analysis),
                                       {request.song}, "--beats-out");
    if (code != ExitCode::Ok) return code;
  }
  if (request.click) {
    audio::MonoAudio mixed{music::mix_click_track(song->samples, song->sample_rate, analysis->map),
                           song->sample_rate};
    if (Status written = writer.write_wav(*request.click, mixed); !written) {
      return fail(ctx, ExitCode::FileError, written.error().message);
    }
    summarize(ctx, "wrote " + *request.click + " (the song with a click on every beat, higher on " +
                       "each bar's first)");
  }
  return ExitCode::Ok;
}

void add_beats_command(CLI::App& app, Context& ctx, Outcome& result) {
  auto request = std::make_shared<BeatsRequest>();
  auto meter = std::make_shared<std::string>();
  CLI::App* cmd =
      app.add_subcommand("beats", "Find a song's beats and print its tempo map as a music: block");
  cmd->add_option("SONG", request->song, "The audio file (WAV, FLAC, Ogg Vorbis, Opus, MP3)")
      ->required();
  cmd->add_option("--meter", *meter,
                  "Beats per bar and beat unit, e.g. 3/4 (default: detected,\n"
                  "2/4, 3/4, 4/4 or 6/8)");
  cmd->add_option("--tempo-hint", request->tempo_hint,
                  "About how fast, in BPM: picks between half, the detected and double tempo")
      ->check(CLI::Range(20.0, 400.0));
  cmd->add_option("--click", request->click,
                  "Also write OUT.wav: the song with a click on every beat");
  cmd->add_option("--beats-out", request->beats_out,
                  "Also write OUT: each beat's time and place in its bar, one per line");
  cmd->callback([&ctx, &result, request, meter] {
    BeatsRequest r = *request;
    if (!meter->empty()) {
      r.meter = music::parse_meter(*meter);
      if (!r.meter) {
        result.code =
            usage_error(ctx, "--meter " + *meter +
                                 ": give beats per bar and a beat unit, e.g. 4/4, 3/4 or 6/8");
        return;
      }
    }
    // The real decoder and encoder; tests call run_beats with their own.
    audio::SndfileAudioReader reader;
    audio::SndfileAudioWriter writer;
    result.code = run_beats(ctx, r, reader, writer);
  });
}

}  // namespace seqc::cli
