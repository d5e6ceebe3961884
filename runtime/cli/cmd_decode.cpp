// seqc decode FILE.hex|-: frames back into an action table; exit 1 if anything is inconsistent.
#include <iterator>
#include <sstream>
#include <string>

#include "compiler/backend/decode.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/protocol/bytes.hpp"

namespace seqc::cli {
namespace {

// '#' starts a comment that runs to the end of the line, so a listing's hex lines can be
// pasted with notes and `seqc upload --dry-run` ("55 55 02 07  # GroupStop") reads back.
std::string strip_comments(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  std::string out;
  while (std::getline(in, line)) {
    out += line.substr(0, line.find('#')) + "\n";
  }
  return out;
}

}  // namespace

void add_decode_command(CLI::App& app, Context& ctx, Outcome& result) {
  auto file = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "decode", "Decode servo controller frames (hex) into a readable action table");
  cmd->add_option("FILE", *file,
                  "Hex frames, as `seqc compile --emit hex` writes them; - for stdin")
      ->required();
  cmd->callback([&ctx, &result, file] {
    std::string text;
    if (*file == "-") {
      if (ctx.in == nullptr) {
        ctx.err << "seqc: error: no standard input\n";
        result.code = ExitCode::FileError;
        return;
      }
      text.assign(std::istreambuf_iterator<char>(*ctx.in), std::istreambuf_iterator<char>());
    } else {
      auto read = ctx.files.read(*file);
      if (!read) {
        ctx.err << "seqc: error: " << read.error().message << "\n";
        result.code = ExitCode::FileError;
        return;
      }
      text = std::move(*read);
    }
    auto bytes = parse_hex(strip_comments(text));
    if (!bytes) {
      ctx.err << "seqc: error: " << *file << ": " << bytes.error().message << "\n";
      result.code = ExitCode::InvalidInput;
      return;
    }
    backend::DecodeResult decoded = backend::decode_frames(*bytes);
    ctx.out << decoded.table;
    if (!decoded.issues.empty()) {
      ctx.err << "seqc: warning: " << *file << ": " << decoded.issues.size() << " inconsistenc"
              << (decoded.issues.size() == 1 ? "y" : "ies") << " (marked '!' in the table)\n";
    }
    result.code = decoded.issues.empty() ? ExitCode::Ok : ExitCode::InvalidInput;
  });
}

}  // namespace seqc::cli
