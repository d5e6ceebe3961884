// The driver's entry for a file that may be either kind: a choreography (compile.hpp) or a show
// (show.hpp), read once.
//
// load() reads the file at `path` once through the FileReader, tells from that text whether it
// is a show file (a top-level `show:` key, is_show_text), and compiles it as one or the other;
// compile_file() and load_show() are handed the text already read, so the main file is never
// read twice (its includes, and a show's performers, are read as usual). A file the reader says
// is over the loader's size limit is not read at all: it is compiled as a choreography, whose
// loader refuses it with the limit's error. A file that cannot be read is a choreography whose
// read_error says why (so a loaded show's own read_error is never set).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "base/diagnostics.hpp"
#include "base/source.hpp"
#include "compiler/compile.hpp"
#include "compiler/show.hpp"

namespace seqc::compiler {

// Serves the file at `path` from `text`, already read (by load(), or from standard input), and
// every other path (its includes, a show's performers) from the reader underneath. size() is the
// reader underneath's for every other path; for `path`, whose text is in hand, it is nullopt, so
// the loader checks the size of the text it is given.
class ReadOnceReader final : public FileReader {
 public:
  ReadOnceReader(std::string path, std::string text, FileReader& rest)
      : path_(std::move(path)), text_(std::move(text)), rest_(rest) {}
  Result<std::string> read(const std::string& path) override;
  std::optional<std::uint64_t> size(const std::string& path) override;

 private:
  std::string path_;
  std::string text_;
  FileReader& rest_;
};

struct LoadOptions {
  CompileOptions program;     // for a choreography file
  CompileOptions performers;  // for each performer's file when it is a show file
};

// A loaded file: a compiled program or a show, with what every caller prints the same way
// whichever it is (the file's own sources and diagnostics, or its read error).
class Loaded {
 public:
  explicit Loaded(CompileOutput program) : value_(std::move(program)) {}
  explicit Loaded(ShowOutput show) : value_(std::move(show)) {}

  bool is_show() const { return std::holds_alternative<ShowOutput>(value_); }
  // The one that was loaded: program() when !is_show(), show() when is_show().
  const CompileOutput& program() const { return std::get<CompileOutput>(value_); }
  CompileOutput& program() { return std::get<CompileOutput>(value_); }
  const ShowOutput& show() const { return std::get<ShowOutput>(value_); }
  ShowOutput& show() { return std::get<ShowOutput>(value_); }

  // The file given itself: for a show its own sources and diagnostics (each performer's are in
  // its CompileOutput).
  const SourceManager& sources() const;
  const Diagnostics& diagnostics() const;
  // Set when the file given could not be read.
  const std::optional<std::string>& read_error() const;
  // Every file it read: CompileOutput::inputs() or ShowOutput::inputs().
  std::vector<std::string> inputs() const;

 private:
  std::variant<CompileOutput, ShowOutput> value_;
};

Loaded load(const std::string& path, FileReader& files, const LoadOptions& options);
// Both kinds with the same options.
Loaded load(const std::string& path, FileReader& files, const CompileOptions& options = {});

}  // namespace seqc::compiler
