#include "compiler/load.hpp"

#include <utility>

#include "compiler/frontend/yaml/yaml_tree.hpp"

namespace seqc::compiler {
namespace {

// Serves the main file from the text load() read, every other path from the reader underneath.
class ReadOnceReader final : public FileReader {
 public:
  ReadOnceReader(std::string path, std::string text, FileReader& rest)
      : path_(std::move(path)), text_(std::move(text)), rest_(rest) {}
  Result<std::string> read(const std::string& path) override {
    if (path == path_) return text_;
    return rest_.read(path);
  }
  // As the reader underneath says, for the main file too: where it cannot tell, the loader
  // checks the text's size after reading it, as it would have without this reader.
  std::optional<std::uint64_t> size(const std::string& path) override { return rest_.size(path); }

 private:
  std::string path_;
  std::string text_;
  FileReader& rest_;
};

}  // namespace

const SourceManager& Loaded::sources() const {
  return is_show() ? show().sources : program().sources;
}

const Diagnostics& Loaded::diagnostics() const {
  return is_show() ? show().diagnostics : program().diagnostics;
}

const std::optional<std::string>& Loaded::read_error() const {
  return is_show() ? show().read_error : program().read_error;
}

Loaded load(const std::string& path, FileReader& files, const LoadOptions& options) {
  if (const auto bytes = files.size(path); bytes && *bytes > YamlLimits{}.max_bytes) {
    return Loaded(compile_file(path, files, options.program));
  }
  Result<std::string> text = files.read(path);
  if (!text) {
    CompileOutput unread;
    unread.read_error = text.error().message;
    return Loaded(std::move(unread));
  }
  const bool show = is_show_text(*text);
  ReadOnceReader once(path, std::move(*text), files);
  if (show) return Loaded(load_show(path, once, options.performers));
  return Loaded(compile_file(path, once, options.program));
}

Loaded load(const std::string& path, FileReader& files, const CompileOptions& options) {
  return load(path, files, LoadOptions{options, options});
}

}  // namespace seqc::compiler
