#include "compiler/frontend/file_loader.hpp"

#include <filesystem>

namespace seqc::compiler {

Result<const LoadedFile*> FileLoader::load(const std::string& path) {
  if (auto it = files_.find(path); it != files_.end()) return it->second.get();
  const YamlLimits limits;
  if (const auto bytes = reader_.size(path); bytes && *bytes > limits.max_bytes) {
    // Refused unread: a 30 MB file costs neither the time nor the memory to read it.
    auto file = std::make_unique<LoadedFile>();
    file->path = path;
    file->file = sources_.add(path, "");
    diags_.error(Location{file->file, 1, 1}, too_large_message(*bytes, limits.max_bytes));
    const LoadedFile* result = file.get();
    files_.emplace(path, std::move(file));
    return result;
  }
  Result<std::string> text = reader_.read(path);
  if (!text) return text.error();
  auto file = std::make_unique<LoadedFile>();
  file->path = path;
  file->file = sources_.add(path, std::move(*text));
  file->root = load_yaml(sources_, file->file, diags_);
  if (file->root) alias_uses_.add(*file->root);
  const LoadedFile* result = file.get();
  files_.emplace(path, std::move(file));
  return result;
}

Result<const LoadedFile*> FileLoader::load_included(const std::string& path) {
  auto loaded = load(path);
  if (!loaded) return loaded;
  const LoadedFile& f = **loaded;
  if (!is_choreography(f)) sources_.withhold_lines(f.file);
  return loaded;
}

bool is_choreography(const LoadedFile& f) {
  return f.root && f.root->is_map() && f.root->find("sequence") != nullptr;
}

std::string resolve_include(const std::string& from, const std::string& target) {
  // Pure path arithmetic; nothing here touches the file system.
  std::filesystem::path t(target);
  if (t.is_absolute()) return t.lexically_normal().string();
  std::filesystem::path joined = std::filesystem::path(from).parent_path() / t;
  return joined.lexically_normal().string();
}

}  // namespace seqc::compiler
