#include "runtime/cli/compile_report.hpp"

#include <iterator>
#include <ostream>

#include "runtime/io/disk.hpp"

namespace seqc::cli {
namespace {

// Serves <stdin> from the text read once; every other path (includes) from the disk.
class StdinFirstReader final : public seqc::FileReader {
 public:
  StdinFirstReader(std::string text, seqc::FileReader& rest)
      : text_(std::move(text)), rest_(rest) {}
  seqc::Result<std::string> read(const std::string& path) override {
    if (path == kStdinName) return text_;
    return rest_.read(path);
  }

 private:
  std::string text_;
  seqc::FileReader& rest_;
};

Compiled compile_from(seqc::FileReader& files, const std::string& path, bool strict,
                      seqc::SongReader* songs, std::int32_t clock_ppm) {
  compiler::CompileOptions options{strict};
  options.songs = songs;
  options.clock_ppm = clock_ppm;
  Compiled c{compiler::compile_file(path, files, options)};
  if (c.output.read_error) {
    c.code = ExitCode::FileError;
  } else {
    c.code = c.output.program ? ExitCode::Ok : ExitCode::InvalidInput;
  }
  return c;
}

}  // namespace

Compiled compile_quietly(Context& ctx, const std::string& path, bool strict, SongCheck song,
                         std::int32_t clock_ppm) {
  seqc::SongReader* songs = song == SongCheck::Decode ? ctx.songs : nullptr;
  if (path == "-") {
    std::string text;
    if (ctx.in != nullptr) {
      text.assign(std::istreambuf_iterator<char>(*ctx.in), std::istreambuf_iterator<char>());
    }
    StdinFirstReader reader(std::move(text), ctx.files);
    return compile_from(reader, kStdinName, strict, songs, clock_ppm);
  }
  return compile_from(ctx.files, path, strict, songs, clock_ppm);
}

}  // namespace seqc::cli

namespace seqc::cli {

Compiled compile_and_report(Context& ctx, const std::string& path, bool strict, SongCheck song,
                            std::int32_t clock_ppm) {
  Compiled c = compile_quietly(ctx, path, strict, song, clock_ppm);
  if (c.output.read_error) {
    ctx.err << "seqc: error: " << *c.output.read_error << "\n";
    return c;
  }
  ctx.err << seqc::render_all(c.output.diagnostics, c.output.sources, strict, ctx.color);
  return c;
}

ExitCode write_output(Context& ctx, const std::string& path, const std::string& data) {
  if (path == "-") {
    ctx.out << data;
    return ExitCode::Ok;
  }
  if (auto written = io::write_file_atomically(path, data); !written) {
    ctx.err << "seqc: error: cannot write '" << path << "': " << written.error().message << "\n";
    return ExitCode::FileError;
  }
  return ExitCode::Ok;
}

compiler::ShowOutput load_show_and_report(Context& ctx, const std::string& path, bool strict,
                                          ExitCode& code) {
  compiler::ShowOutput show = compiler::load_show(path, ctx.files, {strict});
  if (show.read_error) {
    ctx.err << "seqc: error: " << *show.read_error << "\n";
    code = ExitCode::FileError;
    return show;
  }
  ctx.err << seqc::render_all(show.diagnostics, show.sources, strict, ctx.color);
  for (const compiler::Performer& p : show.performers) {
    ctx.err << seqc::render_all(p.output.diagnostics, p.output.sources, strict, ctx.color);
  }
  code = show.ok(strict) ? ExitCode::Ok : ExitCode::InvalidInput;
  return show;
}

}  // namespace seqc::cli
