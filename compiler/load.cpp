#include "compiler/load.hpp"

#include <utility>

#include "compiler/frontend/yaml/yaml_tree.hpp"

namespace seqc::compiler {

Result<std::string> ReadOnceReader::read(const std::string& path) {
  if (path == path_) return text_;
  return rest_.read(path);
}

std::optional<std::uint64_t> ReadOnceReader::size(const std::string& path) {
  if (path == path_) return std::nullopt;
  return rest_.size(path);
}

const SourceManager& Loaded::sources() const {
  return is_show() ? show().sources : program().sources;
}

const Diagnostics& Loaded::diagnostics() const {
  return is_show() ? show().diagnostics : program().diagnostics;
}

const std::optional<std::string>& Loaded::read_error() const {
  return is_show() ? show().read_error : program().read_error;
}

std::vector<std::string> Loaded::inputs() const {
  return is_show() ? show().inputs() : program().inputs();
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
