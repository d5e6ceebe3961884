#include "compiler/show.hpp"

#include <sstream>

#include <fmt/format.h>

#include "compiler/frontend/file_loader.hpp"
#include "compiler/frontend/reporter.hpp"
#include "compiler/frontend/yaml/yaml_tree.hpp"

namespace seqc::compiler {

std::vector<std::string> ShowOutput::inputs() const {
  std::vector<std::string> files;
  for (std::uint32_t f = 0; f < sources.file_count(); ++f) files.push_back(sources.path(f));
  for (const Performer& p : performers) {
    const std::vector<std::string> more = p.output.inputs();
    files.insert(files.end(), more.begin(), more.end());
  }
  return files;
}

bool ShowOutput::ok(bool strict) const {
  if (read_error || diagnostics.has_errors(strict)) return false;
  for (const Performer& p : performers) {
    if (!p.output.program) return false;
  }
  return !performers.empty();
}

const Song* song_of(const CompileOutput& compiled) {
  if (const ServoProgram* p = compiled.servo_program(); p && p->timeline.song) {
    return &*p->timeline.song;
  }
  if (const RaspblockProgram* p = compiled.raspblock_program(); p && p->timeline.song) {
    return &*p->timeline.song;
  }
  return nullptr;
}

ShowSong show_song(const ShowOutput& show) {
  ShowSong r;
  for (const Performer& p : show.performers) {
    const Song* mine = song_of(p.output);
    if (mine == nullptr) continue;
    if (r.song == nullptr) {
      r.song = mine;
      r.first = &p;
    } else if (!same_song(*mine, *r.song)) {
      r.other_song = mine;
      r.other = &p;
      return r;
    }
  }
  return r;
}

std::string different_songs_text(const ShowSong& found) {
  const auto at = [](const Song& s) {
    return fmt::format("{} at {:.3f} s", s.file, s.downbeat.value() / 1000);
  };
  return "performers '" + found.first->name + "' and '" + found.other->name +
         "' dance to different songs or downbeats (" + at(*found.song) + ", " +
         at(*found.other_song) + ")";
}

std::string no_one_song(const ShowOutput& show, const ShowSong& found) {
  if (found.other != nullptr) return different_songs_text(found) + "; a show plays one song";
  if (found.song != nullptr) return "";
  return "no performer of show " + show.name +
         " has a `music:` block, so there is no song to play (docs/music.md)";
}

bool is_show_text(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("show:", 0) == 0) return true;
  }
  return false;
}

ShowOutput load_show(const std::string& path, FileReader& files, const CompileOptions& options) {
  ShowOutput show;
  auto text = files.read(path);
  if (!text) {
    show.read_error = text.error().message;
    return show;
  }
  const std::uint32_t file = show.sources.add(path, std::move(*text));
  const std::optional<YamlNode> root = load_yaml(show.sources, file, show.diagnostics, {});
  if (!root) return show;
  Reporter reporter(show.diagnostics);
  if (!root->is_map()) {
    reporter.error(root->location, "a show file is a map with 'show' and 'performers' keys");
    return show;
  }
  reporter.check_keys(*root, {"show", "description", "performers"}, "in a show file");
  reporter.check_free_text(*root);
  if (const YamlNode* name = root->find("show"); name != nullptr && name->is_scalar()) {
    show.name = name->scalar;
  }
  const YamlNode* performers = root->find("performers");
  if (performers == nullptr || !performers->is_map() || performers->entries.empty()) {
    reporter.error(performers ? performers->location : root->location,
                   "'performers' must map each performer's name to {file, port}, e.g. "
                   "'arm: {file: arm.yaml, port: /dev/ttyUSB0}'");
    return show;
  }
  for (const auto& [key, value] : performers->entries) {
    Performer p;
    p.name = key.scalar;
    p.at = key.location;
    if (!value.is_map()) {
      reporter.error(value.location, "performer '" + p.name + "' needs {file, port}");
      continue;
    }
    reporter.check_keys(value, {"file", "port", "group"}, "in a performer");
    const YamlNode* f = value.find("file");
    if (f == nullptr || !f->is_scalar() || f->scalar.empty()) {
      reporter.error(value.location, "performer '" + p.name +
                                         "' needs a 'file': its "
                                         "choreography, e.g. 'file: arm.yaml'");
      continue;
    }
    if (const YamlNode* port = value.find("port"); port != nullptr && port->is_scalar()) {
      p.port = port->scalar;
    }
    if (const YamlNode* g = value.find("group")) {
      try {
        std::size_t used = 0;
        p.group = std::stoi(g->scalar, &used);
        if (used != g->scalar.size() || p.group < 0 || p.group > 254) throw std::out_of_range("");
      } catch (const std::exception&) {
        reporter.error(g->location, "'group' must be 0-254, not " + g->scalar);
        continue;
      }
    }
    p.file = resolve_include(path, f->scalar);
    p.output = compile_file(p.file, files, options);
    if (p.output.read_error) {
      reporter.error(f->location,
                     "cannot read performer '" + p.name + "': " + *p.output.read_error);
    }
    show.performers.push_back(std::move(p));
  }
  if (const ShowSong found = show_song(show); found.other != nullptr) {
    reporter.warning(found.other->at, different_songs_text(found) +
                                          "; a show plays one song, so `seqc show "
                                          "--music` would refuse it");
  }
  return show;
}

}  // namespace seqc::compiler
