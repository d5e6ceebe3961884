// seqc studio FILE [--http-port N] [--port PORT]: the preview page of FILE, live, served on the
// loopback address (runtime/studio/server.hpp) until Ctrl-C or the page is closed. The URL, with
// its token, is the one line on stdout; the page follows every save of the file, anything it
// includes and its song.
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "base/diagnostics.hpp"
#include "base/terminal_text.hpp"
#include "compiler/formats/preview_html.hpp"
#include "compiler/formats/program_views.hpp"
#include "compiler/show.hpp"
#include "runtime/boards/board_link.hpp"
#include "runtime/cli/board_text.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/cli/compile_report.hpp"
#include "runtime/cli/trace_option.hpp"
#include "runtime/io/disk.hpp"
#include "runtime/studio/robot_follower.hpp"
#include "runtime/studio/server.hpp"

namespace seqc::cli {
namespace {

// The most the studio reads of a song to serve it: a song is played as it is on disk, so it may
// be larger than a choreography's limit.
constexpr std::size_t kMaxSongBytes = 256u << 20;

// Every diagnostic of the file (a show's own, then each performer's) as the terminal shows them,
// without colour, or its read error.
std::string diagnostics_text(const compiler::Loaded& file) {
  if (file.read_error()) return "seqc: error: " + *file.read_error() + "\n";
  std::string text = render_all(file.diagnostics(), file.sources());
  if (file.is_show()) {
    for (const compiler::Performer& p : file.show().performers) {
      text += render_all(p.output.diagnostics, p.output.sources);
    }
  }
  return text;
}

// One compile of `path` as the studio's page shows it, the song fetched from `song_url`.
studio::StudioView studio_view(Context& ctx, const std::string& path,
                               const studio::SongUrl& song_url,
                               std::optional<std::string>& read_error) {
  Loaded loaded = load_quietly(ctx, path, false);
  compiler::Loaded& file = loaded.file;
  studio::StudioView view;
  view.diagnostics = diagnostics_text(file);
  view.inputs = file.inputs();
  // The file itself even when it could not be read: its coming back is a change.
  if (std::find(view.inputs.begin(), view.inputs.end(), path) == view.inputs.end()) {
    view.inputs.insert(view.inputs.begin(), path);
  }
  read_error = file.read_error();
  if (loaded.code != ExitCode::Ok) return view;
  const std::string name = std::filesystem::path(path).filename().string();
  const compiler::Song* song = nullptr;
  if (file.is_show()) {
    const compiler::ShowOutput& show = file.show();
    std::vector<compiler::ShowPart> parts;
    for (const compiler::Performer& p : show.performers) {
      const std::string performer_file = std::filesystem::path(p.file).filename().string();
      parts.push_back({&*p.output.program, part_title(p.output, performer_file, p.group), p.name});
    }
    if (const compiler::ShowPart* with_song = compiler::show_song_part(parts)) {
      for (const compiler::Performer& p : show.performers) {
        if (&*p.output.program == with_song->program) song = compiler::song_of(p.output);
      }
    }
    const std::string url = song != nullptr ? song_url(song->file) : "";
    view.page = compiler::preview_show(parts, name, show.name, ctx.songs, &ctx.files, nullptr, url);
  } else {
    const compiler::CompileOutput& output = file.program();
    song = compiler::song_of(output);
    const std::string url = song != nullptr ? song_url(song->file) : "";
    view.page = compiler::preview_program(*output.program, part_title(output, name, 0), ctx.songs,
                                          ctx.files, nullptr, url);
  }
  if (view.page.empty()) {
    view.diagnostics += "seqc: error: " + name + ": the preview cannot show this kind of program\n";
    return view;
  }
  view.ok = true;
  if (song != nullptr && !compiler::audio_mime(song->file).empty()) {
    view.song_path = song->file;
    view.song_mime = compiler::audio_mime(song->file);
  }
  if (!file.is_show()) {
    view.program = std::make_shared<const compiler::CompileOutput>(std::move(file.program()));
  }
  return view;
}

}  // namespace

void add_studio_command(CLI::App& app, Context& ctx, Outcome& result) {
  struct Options {
    std::string file;
    int http_port = 0;
    std::string port;
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "studio", "Serve the preview page live on this computer: it follows every save of the file");
  cmd->add_option("FILE", o->file, "Choreography or show file (.yaml)")->required();
  cmd->add_option("--http-port", o->http_port,
                  "Serve on this port of 127.0.0.1 (default: any free)")
      ->check(CLI::Range(0, 65535));
  cmd->add_option("--port", o->port, "A robot that follows the page's playhead (its port)");
  cmd->callback([&ctx, &result, o] {
    if (o->file == "-") {
      result.code = usage_error(ctx, "studio needs a file to watch, not standard input");
      return;
    }
    // With --port, the robot follows the page: the board is the one the file is for, so the
    // file must compile once before the port is opened; later saves may break it (the robot then
    // keeps the last good dance, as the page does).
    std::optional<Loaded> first;
    const boards::Board* board = nullptr;
    if (!o->port.empty()) {
      first.emplace(load_quietly(ctx, o->file, false));
      if (first->code != ExitCode::Ok || first->file.is_show()) {
        result.code = first->code != ExitCode::Ok
                          ? fail(ctx, first->code,
                                 o->file + " must compile before the robot can follow it:\n" +
                                     diagnostics_text(first->file))
                          : usage_error(ctx,
                                        "--port follows one robot: a show's performers "
                                        "bring their own ports; use `seqc show` to run it");
        return;
      }
      board = &boards::board_for(first->file.program());
    }
    boards::TraceFile trace;
    std::optional<boards::BoardLink> link;
    std::unique_ptr<studio::PlayheadSink> follower;
    if (board != nullptr) {
      link.emplace(
          boards::open_link({o->port, board}, trace, ctx.clock, ctx.hooks, ctx.interrupted));
      if (!link->port) {
        result.code = say_port_failure(ctx, *link, o->file);
        return;
      }
      if (link->port->own_clock()) {
        result.code =
            usage_error(ctx, o->port +
                                 " runs in emulated time, which a page playing on the wall clock "
                                 "cannot follow; use `seqc emulate " +
                                 std::string(board->key) + "` and its terminal as --port");
        return;
      }
      follower = studio::make_robot_follower(*board, *link->transport, *link->port->clock);
    }
    io::DiskFileReader song_files(kMaxSongBytes);
    studio::DiskStamps stamps;
    studio::DevUrandom random;
    std::optional<std::string> read_error;
    studio::ServerOptions options;
    options.http_port = o->http_port;
    options.sink = follower.get();
    if (ctx.verbosity > 0) {
      options.log = [&ctx](const std::string& line) {
        ctx.err << "seqc: studio: " << line << "\n";
      };
    }
    studio::Server server(
        options,
        [&ctx, o, &read_error](const studio::SongUrl& url) {
          return studio_view(ctx, o->file, url, read_error);
        },
        song_files, stamps, random);
    stop_cleanly_from_now(ctx);
    if (Status started = server.start(); !started) {
      result.code = fail(ctx, read_error ? ExitCode::FileError : ExitCode::PortUnavailable,
                         started.error().message);
      return;
    }
    if (read_error) {
      result.code = fail(ctx, ExitCode::FileError, terminal_safe(*read_error));
      return;
    }
    ctx.out << "seqc: studio at " << server.url() << std::endl;
    summarize(ctx, "studio: " + o->file + (server.ok() ? "" : " has errors (the page shows them)") +
                       "; the page follows its saves; Ctrl-C or closing the page ends it");
    const studio::Server::End end = server.run(ctx.interrupted);
    result.code = end == studio::Server::End::Interrupted ? ExitCode::Interrupted : ExitCode::Ok;
  });
}

}  // namespace seqc::cli
