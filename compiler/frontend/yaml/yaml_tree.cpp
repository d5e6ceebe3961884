// The guarded YAML loader.
//
// Why the event API: yaml-cpp's node API resolves aliases into shared nodes (a billion-laughs
// file expands in memory, a self-referencing anchor makes a cycle) and converts tagged scalars
// eagerly (a "!!binary" value that is not base64 crashes the conversion). With the event API
// nothing is built that this file does not build itself, and the handler can stop the parse at
// the first event it dislikes by throwing Abort, which yaml-cpp unwinds like its own errors.
//
// What yaml-cpp 0.7.0's event parser does with hostile input, and the guard against each, was
// found by experiment; the findings (numbered, and cited by number below) are in
// docs/yaml-loader.md.
//
// Marks: yaml-cpp's are 0-based and count bytes; a leading byte-order mark is stripped before
// parsing, so line 1 columns are shifted back by its 3 bytes.
//
// Errors that leave the tree trustworthy (a duplicate key, a non-scalar key, an unsupported tag)
// are collected and parsing goes on, so one run reports them all; the offending map entries are
// left out of the tree. Everything else stops the parse and load_yaml returns nullopt.
//
// `quoted` is true for every scalar yaml-cpp reports with the non-specific tag "!": quoted
// scalars, block scalars ('|', '>') and scalars explicitly tagged "!". All of them are strings
// in YAML's core schema, which is what the flag is for.
#include "compiler/frontend/yaml/yaml_tree.hpp"

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/exceptions.h>
#include <yaml-cpp/mark.h>
#include <yaml-cpp/parser.h>

#include <sstream>
#include <string_view>
#include <unordered_map>

#include "compiler/frontend/yaml/yaml_prescan.hpp"

namespace seqc::compiler {

const YamlNode* YamlNode::find(std::string_view key) const {
  if (kind != Kind::Map) return nullptr;
  for (const auto& [k, v] : entries) {
    if (k.kind == Kind::Scalar && k.scalar == key) return &v;
  }
  return nullptr;
}

namespace {

constexpr std::string_view kBom = "\xEF\xBB\xBF";
constexpr std::string_view kCoreTagPrefix = "tag:yaml.org,2002:";

// Thrown out of the event handler to stop yaml-cpp; the diagnostic is already recorded.
struct Abort {};

// Keys and tags are quoted in messages; a hostile megabyte-long key must not be.
std::string shorten(std::string_view s) {
  constexpr std::size_t kMax = 40;
  if (s.size() <= kMax) return std::string(s);
  std::size_t cut = kMax;
  while (cut > 0 && (static_cast<unsigned char>(s[cut]) & 0xC0) == 0x80) --cut;
  return std::string(s.substr(0, cut)) + "...";
}

// The tag as the user would have written it.
std::string tag_as_written(const std::string& tag) {
  if (tag.rfind(kCoreTagPrefix, 0) == 0) return "!!" + tag.substr(kCoreTagPrefix.size());
  if (!tag.empty() && tag[0] == '!') return tag;
  return "!<" + tag + ">";
}

// The UTF-8 character at text[pos], for "unexpected 'x'" messages.
std::string char_at(std::string_view text, std::size_t pos) {
  if (pos >= text.size()) return "end of file";
  std::size_t len = 1;
  while (pos + len < text.size() && (static_cast<unsigned char>(text[pos + len]) & 0xC0) == 0x80) {
    ++len;
  }
  return std::string(text.substr(pos, len));
}

class TreeBuilder final : public YAML::EventHandler {
 public:
  TreeBuilder(std::string_view text, std::size_t bom, std::uint32_t file, Diagnostics& diags,
              const YamlLimits& limits)
      : text_(text), bom_(bom), file_(file), diags_(diags), limits_(limits) {}

  Location location(const YAML::Mark& m) const {
    if (m.is_null() || m.line < 0 || m.column < 0) return Location{file_, 0, 0};
    const auto column = static_cast<std::uint32_t>(m.column) + 1 +
                        (m.line == 0 ? static_cast<std::uint32_t>(bom_) : 0u);
    return Location{file_, static_cast<std::uint32_t>(m.line) + 1, column};
  }

  std::optional<YamlNode> take_root() { return std::move(root_); }

  void OnDocumentStart(const YAML::Mark& mark) override {
    if (documents_++ == 0) return;
    const std::size_t pos = offset(mark);
    fail(location(mark),
         text_.substr(pos, 3) == "---"
             ? "more than one document in the file ('---' starts a second one)"
             : "unexpected '" + char_at(text_, pos) + "' after the end of the document");
  }
  void OnDocumentEnd() override {}

  void OnAnchor(const YAML::Mark& mark, const std::string& /*name*/) override {
    fail(location(mark), "anchors and aliases are not supported");
  }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t /*anchor*/) override {
    fail(location(mark), "anchors and aliases are not supported");
  }

  void OnNull(const YAML::Mark& mark, YAML::anchor_t /*anchor*/) override {
    count_node(mark);
    const std::size_t pos = offset(mark);
    if (pos < text_.size() && text_[pos] == '!') {  // finding 4: a tag OnNull does not report
      std::size_t end = pos;
      while (end < text_.size() && text_[end] != ' ' && text_[end] != '\t' && text_[end] != '\n' &&
             text_[end] != '\r') {
        ++end;
      }
      const std::string_view tag = text_.substr(pos, end - pos);
      if (tag != "!") diags_.error(location(mark), "tag '" + shorten(tag) + "' is not supported");
    }
    YamlNode node;
    node.location = location(mark);
    complete(std::move(node));
  }

  void OnScalar(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t /*anchor*/,
                const std::string& value) override {
    scalar(mark, tag, value);
  }

  void OnSequenceStart(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t /*anchor*/,
                       YAML::EmitterStyle::value /*style*/) override {
    open(mark, tag, YamlNode::Kind::Sequence);
  }
  void OnSequenceEnd() override { close(); }

  void OnMapStart(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t /*anchor*/,
                  YAML::EmitterStyle::value /*style*/) override {
    open(mark, tag, YamlNode::Kind::Map);
  }
  void OnMapEnd() override { close(); }

 private:
  struct Frame {
    YamlNode node;
    std::optional<YamlNode> key;  // a map's key waiting for its value
    bool key_usable = false;
    // Duplicate keys are found by hash: small maps scan key_hashes (parallel to node.entries),
    // big ones (a hostile file) get key_index, so neither copies a key.
    std::vector<std::size_t> key_hashes;
    std::unordered_multimap<std::size_t, std::size_t> key_index;  // hash -> entry
  };

  static constexpr std::size_t kScannedKeys = 32;

  // The entry of `top` whose key is `key` (with hash `hash`), or nullptr.
  static const YamlNode* find_key(Frame& top, std::size_t hash, const std::string& key) {
    const auto& entries = top.node.entries;
    if (top.key_index.empty() && entries.size() < kScannedKeys) {
      for (std::size_t i = 0; i < entries.size(); ++i) {
        if (top.key_hashes[i] == hash && entries[i].first.scalar == key) return &entries[i].first;
      }
      return nullptr;
    }
    if (top.key_index.empty()) {
      for (std::size_t i = 0; i < entries.size(); ++i) top.key_index.emplace(top.key_hashes[i], i);
    }
    const auto [begin, end] = top.key_index.equal_range(hash);
    for (auto it = begin; it != end; ++it) {
      if (entries[it->second].first.scalar == key) return &entries[it->second].first;
    }
    return nullptr;
  }

  void scalar(const YAML::Mark& mark, const std::string& tag, std::string_view value) {
    count_node(mark);
    check_tag(mark, tag);
    const std::size_t pos = offset(mark);
    if (tag == "!" && pos < text_.size() && (text_[pos] == '"' || text_[pos] == '\'') &&
        !yaml_detail::quoted_scalar_closes(text_, pos)) {  // finding 3
      fail(location(mark), "unterminated quoted string");
    }
    YamlNode node;
    node.kind = YamlNode::Kind::Scalar;
    node.location = location(mark);
    node.scalar = value;
    node.quoted = tag == "!";
    complete(std::move(node));
  }

  [[noreturn]] void fail(Location at, std::string message) {
    diags_.error(at, std::move(message));
    throw Abort{};
  }

  std::size_t offset(const YAML::Mark& m) const {
    return m.pos < 0 ? text_.size() : static_cast<std::size_t>(m.pos) + bom_;
  }

  void count_node(const YAML::Mark& mark) {
    if (++nodes_ > limits_.max_nodes) {
      fail(location(mark),
           "the file has more than " + std::to_string(limits_.max_nodes) + " YAML nodes");
    }
  }

  void check_tag(const YAML::Mark& mark, const std::string& tag) {
    if (tag.empty() || tag == "?" || tag == "!") return;
    diags_.error(location(mark), "tag '" + shorten(tag_as_written(tag)) + "' is not supported");
  }

  void open(const YAML::Mark& mark, const std::string& tag, YamlNode::Kind kind) {
    count_node(mark);
    check_tag(mark, tag);
    if (stack_.size() >= limits_.max_depth) {
      fail(location(mark),
           "nesting is deeper than " + std::to_string(limits_.max_depth) + " levels");
    }
    Frame f;
    f.node.kind = kind;
    f.node.location = location(mark);
    stack_.push_back(std::move(f));
  }

  void close() {
    YamlNode node = std::move(stack_.back().node);
    stack_.pop_back();
    complete(std::move(node));
  }

  // A finished node goes to its parent: the document, a sequence, or a map as key or value.
  void complete(YamlNode node) {
    if (stack_.empty()) {
      root_ = std::move(node);
      return;
    }
    Frame& top = stack_.back();
    if (top.node.kind == YamlNode::Kind::Sequence) {
      top.node.items.push_back(std::move(node));
      return;
    }
    if (!top.key) {
      top.key_usable = node.kind == YamlNode::Kind::Scalar;
      if (node.kind == YamlNode::Kind::Null) {
        diags_.error(node.location, "map key is empty or null");
      } else if (!top.key_usable) {
        diags_.error(node.location, "map keys must be scalars, not a " +
                                        std::string(node.is_map() ? "map" : "sequence"));
      }
      top.key = std::move(node);
      return;
    }
    YamlNode key = std::move(*top.key);
    top.key.reset();
    if (!top.key_usable) return;
    const std::size_t hash = std::hash<std::string_view>{}(key.scalar);
    if (const YamlNode* first = find_key(top, hash, key.scalar)) {
      diags_.error(key.location, "duplicate key '" + shorten(key.scalar) + "'");
      diags_.note(first->location, "first defined here");
      return;
    }
    if (!top.key_index.empty()) top.key_index.emplace(hash, top.node.entries.size());
    top.key_hashes.push_back(hash);
    top.node.entries.push_back({std::move(key), std::move(node)});
  }

  std::string_view text_;  // the whole file, byte-order mark included
  std::size_t bom_;
  std::uint32_t file_;
  Diagnostics& diags_;
  const YamlLimits& limits_;
  std::vector<Frame> stack_;
  std::optional<YamlNode> root_;
  std::size_t nodes_ = 0;
  int documents_ = 0;
};

// yaml-cpp's own messages are terse but accurate; two are rephrased in this loader's terms.
std::string parser_message(const YAML::Exception& e, const YamlLimits& limits) {
  if (e.msg == "the referenced anchor is not defined") {
    return "anchors and aliases are not supported";
  }
  if (dynamic_cast<const YAML::DeepRecursion*>(&e) != nullptr) {
    return "nesting is deeper than " + std::to_string(limits.max_depth) + " levels";
  }
  return "invalid YAML: " + e.msg;
}

}  // namespace

std::string too_large_message(std::uint64_t bytes, std::size_t limit) {
  return "file is " + std::to_string(bytes) + " bytes; the limit is " + std::to_string(limit) +
         " bytes";
}

std::optional<YamlNode> load_yaml(const SourceManager& sources, std::uint32_t file,
                                  Diagnostics& diags, const YamlLimits& limits) {
  const std::string& text = sources.text(file);
  if (text.size() > limits.max_bytes) {
    diags.error(Location{file, 1, 1} /* the whole file */,
                too_large_message(text.size(), limits.max_bytes));
    return std::nullopt;
  }
  if (auto problem = yaml_detail::check_bytes(text)) {
    diags.error(Location{file, problem->line, problem->column}, std::move(problem->message));
    return std::nullopt;
  }
  const std::size_t bom = std::string_view(text).substr(0, kBom.size()) == kBom ? kBom.size() : 0;
  const std::string_view body = std::string_view(text).substr(bom);

  TreeBuilder builder(text, bom, file, diags, limits);
  try {
    if (auto problem = yaml_detail::check_flow_depth(body, limits.max_depth)) {
      const std::uint32_t shift = problem->line == 1 ? static_cast<std::uint32_t>(bom) : 0u;
      diags.error(Location{file, problem->line, problem->column + shift},
                  std::move(problem->message));
      return std::nullopt;
    }
    std::istringstream in{std::string(body)};
    YAML::Parser parser(in);
    // Finding 1: the second document aborts, so this runs at most twice.
    for (int i = 0; i < 2 && parser.HandleNextDocument(builder); ++i) {
    }
  } catch (const Abort&) {
    return std::nullopt;
  } catch (const YAML::Exception& e) {
    // yaml-cpp notices an unclosed '{' or '[' only at the token where the collection should have
    // ended, often the next line; the mistake is the bracket itself.
    const bool unclosed =
        e.msg == YAML::ErrorMsg::END_OF_MAP_FLOW || e.msg == YAML::ErrorMsg::END_OF_SEQ_FLOW;
    if (unclosed && e.mark.pos >= 0) {
      if (auto open = yaml_detail::unclosed_flow(body, static_cast<std::size_t>(e.mark.pos))) {
        const std::uint32_t shift = open->line == 1 ? static_cast<std::uint32_t>(bom) : 0u;
        diags.error(Location{file, open->line, open->column + shift},
                    "invalid YAML: " + open->message);
        return std::nullopt;
      }
    }
    diags.error(builder.location(e.mark), parser_message(e, limits));
    return std::nullopt;
  }
  std::optional<YamlNode> root = builder.take_root();
  if (!root) {  // an empty file (or only comments and directives): one null document
    root.emplace();
    root->location = Location{file, 1, 1};
  }
  return root;
}

}  // namespace seqc::compiler
