// One reading of a choreography file for the language features (features.hpp): the file and
// the files it includes, loaded as the compiler loads them; its robot; when each step runs, as
// the compiler's own step walk times it (compiler/frontend/step_times.hpp) with the tempo map
// the walk built; and an index of every name written in them (poses, sections, parameters,
// groups, servos, includes, easings and the verb of each step), each with the exact span of
// text it occupies. Nothing here throws on a half-typed or foreign file: what cannot be read is
// simply absent from the index.
//
// Positions: the compiler counts 1-based lines and byte columns; the protocol counts 0-based
// lines and UTF-16 columns. TextPos is the protocol's; to_protocol() and to_byte_column()
// convert on the line's own text.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/diagnostics.hpp"
#include "base/source.hpp"
#include "compiler/frontend/file_loader.hpp"
#include "compiler/frontend/robot_section.hpp"
#include "compiler/frontend/step_times.hpp"
#include "compiler/frontend/yaml/yaml_tree.hpp"
#include "compiler/timeline/tempo_map.hpp"

namespace seqc::lsp {

// A protocol position: 0-based line, UTF-16 column.
struct TextPos {
  std::uint32_t line = 0;
  std::uint32_t character = 0;
};

// A span of one line of one file in the compiler's terms (1-based line, byte column).
struct Span {
  std::uint32_t file = 0;
  std::uint32_t line = 0;
  std::uint32_t column = 0;
  std::uint32_t length = 0;  // bytes
};

enum class NameKind { Pose, Section, Param, Group, Servo, Include, Easing, Step };

struct Name {
  NameKind kind = NameKind::Pose;
  std::string text;         // the name (a parameter without its '$'; an include's path)
  Span span;                // where it is written
  bool definition = false;  // the key that defines it (a pose's, a section's, a parameter's)
  std::string section;      // Param: the section that declares it
  // Pose/Section/Group definition: its value; Step: the step's map; Include: the step's value.
  const compiler::YamlNode* node = nullptr;
  std::string target;  // Include: the path of the file it names
};

class Analysis {
 public:
  // Reads `path` (and its includes) through `files`, and with `walk` times its steps; never
  // fails: a file that cannot be read gives an analysis without files.
  static std::unique_ptr<Analysis> run(const std::string& path, FileReader& files,
                                       bool walk = true);

  Analysis(const Analysis&) = delete;
  Analysis& operator=(const Analysis&) = delete;

  // The main file's index in sources(), nullopt when it could not be read.
  std::optional<std::uint32_t> main_file() const { return main_file_; }
  const SourceManager& sources() const { return sources_; }
  const std::optional<compiler::Robot>& robot() const { return robot_; }
  // The main file's root map, nullptr when it is none.
  const compiler::YamlNode* main_root() const;
  const std::vector<const compiler::LoadedFile*>& files() const { return loaded_; }
  const std::vector<Name>& names() const { return names_; }
  const compiler::StepTimes& times() const { return times_; }
  const compiler::TempoMap& tempo_map() const { return tempo_map_; }
  // Whether the steps were walked (a servo controller's file with a robot).
  bool walked() const { return walked_; }
  // Where time 0 of the sequence falls in the audio of the main file's `music:` song.
  const std::optional<compiler::ExactMs>& downbeat() const { return downbeat_; }

  // The name written at `pos` in `file`, nullptr when none.
  const Name* name_at(std::uint32_t file, TextPos pos) const;
  // Every name of `kind` called `text` (for a parameter: of section `section`).
  std::vector<const Name*> same(const Name& name) const;
  // The definition of `name` (itself when it is one), nullptr when it has none written.
  const Name* definition_of(const Name& name) const;
  // The index of the file at `path` among sources(), if it was read.
  std::optional<std::uint32_t> file_of(std::string_view path) const;

  // Conversions between the compiler's and the protocol's positions on one line.
  TextPos to_protocol(std::uint32_t file, std::uint32_t line, std::uint32_t column) const;
  std::uint32_t to_byte_column(std::uint32_t file, TextPos pos) const;
  std::uint32_t line_end_column(std::uint32_t file, std::uint32_t line) const;

 private:
  Analysis() = default;
  void load_includes(const compiler::LoadedFile& f, std::size_t depth);
  void index_file(const compiler::LoadedFile& f);
  void index_steps(const compiler::YamlNode& list, std::uint32_t file, const std::string& section);
  void index_step(const compiler::YamlNode& step, std::uint32_t file, const std::string& section);
  void index_positions(const compiler::YamlNode& map, std::uint32_t file,
                       const std::string& section);
  void index_params_in(const compiler::YamlNode& node, std::uint32_t file,
                       const std::string& section);
  // Adds a name written as the scalar `node`, when its text can be found where it starts.
  void add(NameKind kind, const compiler::YamlNode& node, std::uint32_t file, bool definition,
           const std::string& section = {}, const compiler::YamlNode* value = nullptr);

  SourceManager sources_;
  Diagnostics diags_;
  std::unique_ptr<compiler::FileLoader> loader_;
  std::optional<std::uint32_t> main_file_;
  std::vector<const compiler::LoadedFile*> loaded_;
  std::optional<compiler::Robot> robot_;
  compiler::StepTimes times_;
  compiler::TempoMap tempo_map_;
  bool walked_ = false;
  std::optional<compiler::ExactMs> downbeat_;
  std::vector<Name> names_;
  std::vector<std::string> group_names_;
};

// The text of `node` as its source shows it: its span when it is a scalar written on one line
// (past an opening quote), nullopt otherwise.
std::optional<Span> scalar_span(const SourceManager& sources, const compiler::YamlNode& node);

}  // namespace seqc::lsp
