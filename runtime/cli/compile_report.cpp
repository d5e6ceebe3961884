#include "runtime/cli/compile_report.hpp"

#include <cerrno>
#include <cstring>
#include <ostream>
#include <utility>

#include "base/terminal_text.hpp"
#include "protocol/lsc/group_download.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/io/disk.hpp"
#include "runtime/transport/port_spec.hpp"

namespace seqc::cli {
namespace {

// `start`: where the robot stands, for a first move relative to it (RobotStart).
compiler::CompileOptions compile_options(Context& ctx, bool strict, SongCheck song,
                                         std::int32_t clock_ppm, bool over_hid, bool chain,
                                         compiler::RobotStart start = {}) {
  return {.strict = strict,
          .songs = song == SongCheck::Decode ? ctx.songs : nullptr,
          .clock_ppm = clock_ppm,
          .over_hid = over_hid,
          .chain = chain,
          .start = std::move(start)};
}

// Where a checked file's robot is taken to stand: at home, said in a note where it matters.
compiler::RobotStart home_start() {
  compiler::RobotStart start;
  start.assume_home = true;
  return start;
}

ExitCode program_code(const compiler::CompileOutput& output) {
  if (output.read_error) return ExitCode::FileError;
  return output.program ? ExitCode::Ok : ExitCode::InvalidInput;
}

ExitCode show_code(const compiler::ShowOutput& show, bool strict) {
  if (show.read_error) return ExitCode::FileError;
  return show.ok(strict) ? ExitCode::Ok : ExitCode::InvalidInput;
}

// The file's read error, or else its diagnostics; false after a read error.
bool report(Context& ctx, const std::optional<std::string>& error, const Diagnostics& diagnostics,
            const SourceManager& sources, bool strict) {
  if (error) ctx.err << "seqc: error: " << terminal_safe(*error) << "\n";
  if (!error) ctx.err << seqc::render_all(diagnostics, sources, strict, ctx.color);
  return !error;
}

// The same, and for a show every performer's diagnostics.
void report(Context& ctx, const compiler::Loaded& file, bool strict) {
  if (!report(ctx, file.read_error(), file.diagnostics(), file.sources(), strict)) return;
  if (!file.is_show()) return;
  for (const compiler::Performer& p : file.show().performers) {
    ctx.err << seqc::render_all(p.output.diagnostics, p.output.sources, strict, ctx.color);
  }
}

}  // namespace

void add_link_port_option(CLI::App& cmd, std::string& port) {
  cmd.add_option("--port", port,
                 "Port the group is for (nothing is opened): over USB HID (hid, hid:PATH, "
                 "emu:xarm-hid) an action holds at most " +
                     std::to_string(lsc::kHidMaxActionServos) + " servos")
      ->check([](const std::string& text) {
        const auto spec = transport::parse_port(text);
        return spec ? std::string() : spec.error().message;
      });
}

Compiled compile_quietly(Context& ctx, const std::string& path, bool strict, SongCheck song,
                         std::int32_t clock_ppm, bool over_hid, bool chain,
                         compiler::RobotStart start) {
  const compiler::CompileOptions options =
      compile_options(ctx, strict, song, clock_ppm, over_hid, chain, std::move(start));
  Compiled c;
  if (path == "-") {
    auto text = io::read_input(path, ctx.files, ctx.in, kStdinName);
    if (!text) {
      c.output.read_error = text.error().message;
      c.code = ExitCode::FileError;
      return c;
    }
    compiler::ReadOnceReader reader(kStdinName, std::move(*text), ctx.files);
    c.output = compiler::compile_file(kStdinName, reader, options);
  } else {
    c.output = compiler::compile_file(path, ctx.files, options);
  }
  c.code = program_code(c.output);
  return c;
}

Compiled compile_and_report(Context& ctx, const std::string& path, bool strict, SongCheck song,
                            const ClockScaleOptions* clock, bool over_hid, bool chain) {
  std::int32_t ppm = 0;
  if (clock != nullptr) {
    if (const ExitCode e = resolve_clock_ppm(ctx, *clock, ppm); e != ExitCode::Ok) return {{}, e};
  }
  Compiled c = compile_quietly(ctx, path, strict, song, ppm, over_hid, chain);
  c.clock_ppm = ppm;
  report(ctx, c.output.read_error, c.output.diagnostics, c.output.sources, strict);
  return c;
}

void report_compile(Context& ctx, const Compiled& c, bool strict) {
  report(ctx, c.output.read_error, c.output.diagnostics, c.output.sources, strict);
}

Loaded load_quietly(Context& ctx, const std::string& path, bool strict, SongCheck song,
                    std::int32_t clock_ppm, bool over_hid) {
  if (path == "-") {
    Compiled c = compile_quietly(ctx, path, strict, song, clock_ppm, over_hid, true, home_start());
    return {compiler::Loaded(std::move(c.output)), c.code};
  }
  // A choreography checked or shown here is checked from home where it moves relative to where
  // the robot stands, and may take any number of groups; a show's performers are stored without
  // reading, one group each, as `upload` stores them.
  compiler::Loaded file =
      compiler::load(path, ctx.files,
                     {compile_options(ctx, strict, song, clock_ppm, over_hid, true, home_start()),
                      compile_options(ctx, strict, song, 0, false, false)});
  const ExitCode code =
      file.is_show() ? show_code(file.show(), strict) : program_code(file.program());
  return {std::move(file), code};
}

Loaded load_and_report(Context& ctx, const std::string& path, bool strict, SongCheck song,
                       std::int32_t clock_ppm, bool over_hid) {
  Loaded l = load_quietly(ctx, path, strict, song, clock_ppm, over_hid);
  report(ctx, l.file, strict);
  return l;
}

void say_stdout_failed(Context& ctx, int error) {
  ctx.err << "seqc: error: " << kStdoutName << ": cannot write"
          << (error != 0 ? std::string(": ") + std::strerror(error) : std::string()) << "\n";
}

bool refuse_input_as_output(Context& ctx, const std::string& option, const std::string& path,
                            const std::vector<std::string>& inputs) {
  const std::string input = io::same_file_among(path, inputs);
  if (input.empty()) return false;
  ctx.err << "seqc: error: " << option << " " << path << " is the same file as the input " << input
          << "; nothing was written\n";
  return true;
}

ExitCode write_stdout(Context& ctx, std::string_view data) {
  errno = 0;
  ctx.out.write(data.data(), static_cast<std::streamsize>(data.size()));
  if (!ctx.out.flush()) {
    say_stdout_failed(ctx, errno);
    return ExitCode::FileError;
  }
  return ExitCode::Ok;
}

ExitCode write_output(Context& ctx, const std::string& path, const std::string& data,
                      const std::vector<std::string>& inputs, const std::string& option) {
  if (path.empty() || path == "-") return write_stdout(ctx, data);
  if (refuse_input_as_output(ctx, option, path, inputs)) return ExitCode::Usage;
  if (auto written = io::write_file_safely(path, data); !written) {
    return fail(ctx, ExitCode::FileError, written.error().message);
  }
  return ExitCode::Ok;
}

compiler::ShowOutput load_show_and_report(Context& ctx, const std::string& path, bool strict,
                                          ExitCode& code) {
  compiler::CompileOptions options;
  options.strict = strict;
  compiler::Loaded show(compiler::load_show(path, ctx.files, options));
  report(ctx, show, strict);
  code = show_code(show.show(), strict);
  return std::move(show.show());
}

}  // namespace seqc::cli
