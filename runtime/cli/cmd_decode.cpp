// seqc decode FILE|- [--from FORMAT]: what seqc wrote or recorded (compile hex, --dry-run,
// --trace, the emulators' --record, Raspblock packets, either servo-controller dialect) back
// into a readable table; exit 1 if anything is inconsistent. The dialect choices of --from are the
// dialect table's (protocol/dialects.hpp).
#include <iterator>
#include <sstream>
#include <string>

#include <CLI/CLI.hpp>

#include "base/bytes.hpp"
#include "compiler/formats/decode_formats.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/io/disk.hpp"

namespace seqc::cli {
void add_decode_command(CLI::App& app, Context& ctx, Outcome& result) {
  auto file = std::make_shared<std::string>();
  auto from = std::make_shared<std::string>("auto");
  CLI::App* cmd = app.add_subcommand(
      "decode",
      "Decode what seqc writes or records (frames, traces, emulator records) into a table");
  cmd->add_option("FILE", *file, "The file; - for stdin")->required();
  cmd->add_option("--from", *from,
                  "auto (default: told apart by content), hex (xArm/LSC-16/LSC-32\n"
                  "frames), lsc6, raspblock, trace or record")
      ->check(CLI::IsMember(compiler::decode_format_names()));
  cmd->callback([&ctx, &result, file, from] {
    if (*file == "-" && ctx.in == nullptr) {
      result.code = fail(ctx, ExitCode::FileError, "no standard input");
      return;
    }
    auto text = io::read_input(*file, ctx.files, ctx.in, "<stdin>");
    if (!text) {
      result.code = fail(ctx, ExitCode::FileError, text.error().message);
      return;
    }
    compiler::DecodeResult decoded =
        compiler::decode_text(*text, compiler::parse_decode_format(*from).value());
    ctx.out << decoded.table;
    if (!decoded.issues.empty()) {
      ctx.err << "seqc: warning: " << *file << ": " << decoded.issues.size() << " inconsistenc"
              << (decoded.issues.size() == 1 ? "y" : "ies") << " (marked '!' in the table)\n";
    }
    result.code = decoded.issues.empty() ? ExitCode::Ok : ExitCode::InvalidInput;
  });
}

}  // namespace seqc::cli
