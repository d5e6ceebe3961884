// The guarded YAML loader.
//
// Why the event API: yaml-cpp's node API resolves aliases into shared nodes (a billion-laughs
// file expands in memory, a self-referencing anchor makes a cycle) and converts tagged scalars
// eagerly (a "!!binary" value that is not base64 crashes the conversion). With the event API
// nothing is built that this file does not build itself, and the handler can stop the parse at
// the first event it dislikes by throwing Abort, which yaml-cpp unwinds like its own errors.
//
// Anchors and aliases: an alias is a copy of its anchored node (so the tree stays a tree), and
// the copy's size and depth are known before it is made: a copy that would take the nodes
// copied in all past YamlLimits::max_alias_nodes, or nest past max_depth, stops the parse at
// that alias, having copied nothing for it. yaml-cpp registers an anchor before the node it
// names is read, so an alias inside its own anchored node does reach the handler: that is an
// error (a cycle), not a copy. Merge keys ('<<', YAML 1.1) are applied when their map ends: the
// map's own keys win, then the merged maps in the order they are listed; the merged entries go
// where the '<<' was.
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

#include <algorithm>
#include <iterator>
#include <sstream>
#include <string_view>
#include <unordered_map>
#include <unordered_set>

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

  std::size_t offset(const YAML::Mark& m) const {
    return m.pos < 0 ? text_.size() : static_cast<std::size_t>(m.pos) + bom_;
  }

  void OnDocumentStart(const YAML::Mark& mark) override {
    if (documents_++ == 0) return;
    const std::size_t pos = offset(mark);
    fail(location(mark),
         text_.substr(pos, 3) == "---"
             ? "more than one document in the file ('---' starts a second one)"
             : "unexpected '" + char_at(text_, pos) + "' after the end of the document");
  }
  void OnDocumentEnd() override {}

  // yaml-cpp calls this just before the event of the node the anchor names.
  void OnAnchor(const YAML::Mark& mark, const std::string& name) override {
    pending_anchor_ = name;
    pending_anchor_at_ = location(mark);
  }

  void OnAlias(const YAML::Mark& mark, YAML::anchor_t id) override {
    const Location at = location(mark);
    // yaml-cpp throws for a name no anchor defined (see undefined_alias_message); an id it
    // never gave to a node event is not expected, and is the same mistake.
    if (id == YAML::NullAnchor || id > anchors_.size()) {
      fail(at, undefined_alias_message(offset(mark)));
    }
    const Anchor& anchor = anchors_[id - 1];
    if (!anchor.node) {
      diags_.error(at, "alias '*" + shorten(anchor.name) +
                           "' is inside the node it refers to (a node cannot contain itself)");
      diags_.note(anchor.at, "anchor '&" + shorten(anchor.name) + "' is here");
      throw Abort{};
    }
    if (anchor.nodes > limits_.max_alias_nodes - aliased_nodes_) {
      fail(at, "aliases expand to more than " + std::to_string(limits_.max_alias_nodes) +
                   " nodes (a YAML \"billion laughs\"?)");
    }
    if (stack_.size() + anchor.depth > limits_.max_depth) {
      fail(at, "nesting is deeper than " + std::to_string(limits_.max_depth) + " levels");
    }
    aliased_nodes_ += anchor.nodes;
    YamlNode copy = *anchor.node;
    mark_used(copy, at);
    complete(std::move(copy));
  }

  // "undefined alias '*x' ...", for the alias whose '*' is at text_[pos].
  std::string undefined_alias_message(std::size_t pos) const {
    std::size_t end = pos + 1;
    while (end < text_.size() && text_[end] != ' ' && text_[end] != '\t' && text_[end] != '\n' &&
           text_[end] != '\r' && text_[end] != ',' && text_[end] != '[' && text_[end] != ']' &&
           text_[end] != '{' && text_[end] != '}') {
      ++end;
    }
    const std::string name = shorten(
        text_.substr(std::min(pos + 1, text_.size()), end - std::min(pos + 1, text_.size())));
    return "undefined alias '*" + name + "' (no anchor '&" + name + "' before it)";
  }

  void OnNull(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    begin_anchor(anchor);
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
    end_anchor(anchor, node);
    complete(std::move(node));
  }

  void OnScalar(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor,
                const std::string& value) override {
    begin_anchor(anchor);
    scalar(mark, tag, anchor, value);
  }

  void OnSequenceStart(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor,
                       YAML::EmitterStyle::value /*style*/) override {
    begin_anchor(anchor);
    open(mark, tag, YamlNode::Kind::Sequence, anchor);
  }
  void OnSequenceEnd() override { close(); }

  void OnMapStart(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor,
                  YAML::EmitterStyle::value /*style*/) override {
    begin_anchor(anchor);
    open(mark, tag, YamlNode::Kind::Map, anchor);
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
    YAML::anchor_t anchor = YAML::NullAnchor;  // the anchor naming this node, if any
    // A merge key: where it was, where its entries go, and the maps it merges in list order.
    std::optional<Location> merge_key;
    std::size_t merge_at = 0;
    std::vector<YamlNode> merge_sources;
  };

  // An anchored node, kept as a copy for the aliases to it; `node` is empty while it is built.
  struct Anchor {
    std::string name;
    Location at;
    std::optional<YamlNode> node;
    std::size_t nodes = 0;  // in the subtree, keys included (as count_node counts them)
    std::size_t depth = 0;  // sequences and maps nested in the subtree, itself included
  };

  void begin_anchor(YAML::anchor_t id) {
    if (id == YAML::NullAnchor) return;
    if (anchors_.size() < id) anchors_.resize(id);
    anchors_[id - 1] = Anchor{std::move(pending_anchor_), pending_anchor_at_, std::nullopt, 0, 0};
    pending_anchor_.clear();
  }

  void end_anchor(YAML::anchor_t id, const YamlNode& node) {
    if (id == YAML::NullAnchor) return;
    Anchor& anchor = anchors_[id - 1];
    anchor.nodes = count_nodes(node);
    anchor.depth = nesting(node);
    anchor.node = node;
  }

  static std::size_t count_nodes(const YamlNode& n) {
    std::size_t total = 1;
    for (const YamlNode& item : n.items) total += count_nodes(item);
    for (const YamlEntry& e : n.entries) total += count_nodes(e.first) + count_nodes(e.second);
    return total;
  }

  static std::size_t nesting(const YamlNode& n) {
    if (n.kind != YamlNode::Kind::Sequence && n.kind != YamlNode::Kind::Map) return 0;
    std::size_t deepest = 0;
    for (const YamlNode& item : n.items) deepest = std::max(deepest, nesting(item));
    for (const YamlEntry& e : n.entries) {
      deepest = std::max({deepest, nesting(e.first), nesting(e.second)});
    }
    return deepest + 1;
  }

  // Nodes inside an earlier copy keep the alias that copied them there (the innermost).
  static void mark_used(YamlNode& n, Location alias) {
    if (n.used_at.line == 0) n.used_at = alias;
    for (YamlNode& item : n.items) mark_used(item, alias);
    for (YamlEntry& e : n.entries) {
      mark_used(e.first, alias);
      mark_used(e.second, alias);
    }
  }

  // The value of a merge key '<<': a map, or a list of maps.
  void add_merge(Frame& top, const YamlNode& key, YamlNode value) {
    if (top.merge_key) {
      diags_.error(key.location, "duplicate key '<<'");
      diags_.note(*top.merge_key, "first defined here");
      return;
    }
    top.merge_key = key.location;
    top.merge_at = top.node.entries.size();
    if (value.is_map()) {
      top.merge_sources.push_back(std::move(value));
      return;
    }
    if (!value.is_sequence()) {
      diags_.error(value.location, "the merge key '<<' takes a map or a list of maps, not " +
                                       std::string(kind_name(value)));
      return;
    }
    for (YamlNode& item : value.items) {
      if (item.is_map()) {
        top.merge_sources.push_back(std::move(item));
      } else {
        diags_.error(item.location, "the merge key '<<' takes a list of maps; this item is " +
                                        std::string(kind_name(item)));
      }
    }
  }

  // The merged maps' entries whose keys the map does not have, earlier maps first, at the '<<'.
  void apply_merge(Frame& f) {
    std::vector<YamlEntry> merged;
    std::unordered_set<std::string> taken;
    for (YamlNode& source : f.merge_sources) {
      for (YamlEntry& e : source.entries) {
        const std::size_t hash = std::hash<std::string_view>{}(e.first.scalar);
        if (find_key(f, hash, e.first.scalar) != nullptr) continue;
        if (!taken.insert(e.first.scalar).second) continue;
        merged.push_back(std::move(e));
      }
    }
    f.merge_sources.clear();
    auto& entries = f.node.entries;
    entries.insert(entries.begin() + static_cast<std::ptrdiff_t>(f.merge_at),
                   std::make_move_iterator(merged.begin()), std::make_move_iterator(merged.end()));
  }

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

  void scalar(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor,
              std::string_view value) {
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
    end_anchor(anchor, node);
    complete(std::move(node));
  }

  [[noreturn]] void fail(Location at, std::string message) {
    diags_.error(at, std::move(message));
    throw Abort{};
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

  void open(const YAML::Mark& mark, const std::string& tag, YamlNode::Kind kind,
            YAML::anchor_t anchor) {
    count_node(mark);
    check_tag(mark, tag);
    if (stack_.size() >= limits_.max_depth) {
      fail(location(mark),
           "nesting is deeper than " + std::to_string(limits_.max_depth) + " levels");
    }
    Frame f;
    f.node.kind = kind;
    f.node.location = location(mark);
    f.anchor = anchor;
    stack_.push_back(std::move(f));
  }

  void close() {
    Frame& top = stack_.back();
    if (!top.merge_sources.empty()) apply_merge(top);
    YamlNode node = std::move(top.node);
    const YAML::anchor_t anchor = top.anchor;
    stack_.pop_back();
    end_anchor(anchor, node);
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
    if (!key.quoted && key.scalar == "<<") {
      add_merge(top, key, std::move(node));
      return;
    }
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
  std::size_t aliased_nodes_ = 0;  // copied by aliases, in all
  std::vector<Anchor> anchors_;    // by yaml-cpp's anchor id, from 1
  std::string pending_anchor_;     // named by OnAnchor for the next node event
  Location pending_anchor_at_;
  int documents_ = 0;
};

// yaml-cpp's own messages are terse but accurate; two are rephrased in this loader's terms.
std::string parser_message(const YAML::Exception& e, const YamlLimits& limits,
                           const TreeBuilder& builder) {
  if (e.msg == YAML::ErrorMsg::UNKNOWN_ANCHOR && e.mark.pos >= 0) {
    return builder.undefined_alias_message(builder.offset(e.mark));
  }
  if (dynamic_cast<const YAML::DeepRecursion*>(&e) != nullptr) {
    return "nesting is deeper than " + std::to_string(limits.max_depth) + " levels";
  }
  return "invalid YAML: " + e.msg;
}

}  // namespace

void AliasUses::add(const YamlNode& root) {
  const auto walk = [this](const auto& self, const YamlNode& n) -> void {
    if (n.used_at.line != 0) {
      auto& list = sites_[std::make_tuple(n.location.file, n.location.line, n.location.column)];
      if (std::find(list.begin(), list.end(), n.used_at) == list.end()) list.push_back(n.used_at);
    }
    for (const YamlNode& item : n.items) self(self, item);
    for (const YamlEntry& e : n.entries) {
      self(self, e.first);
      self(self, e.second);
    }
  };
  walk(walk, root);
}

const std::vector<Location>& AliasUses::sites(Location at) const {
  static const std::vector<Location> kNone;
  const auto it = sites_.find(std::make_tuple(at.file, at.line, at.column));
  return it == sites_.end() ? kNone : it->second;
}

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
    diags.error(builder.location(e.mark), parser_message(e, limits, builder));
    return std::nullopt;
  }
  std::optional<YamlNode> root = builder.take_root();
  if (!root) {  // an empty file (or only comments and directives): one null document
    root.emplace();
    root->location = Location{file, 1, 1};
  }
  return root;
}

std::string_view kind_name(const YamlNode& node) {
  switch (node.kind) {
    case YamlNode::Kind::Null:
      return "empty";
    case YamlNode::Kind::Scalar:
      return "a single value";
    case YamlNode::Kind::Sequence:
      return "a list";
    case YamlNode::Kind::Map:
      return "a map";
  }
  return "a value";
}

}  // namespace seqc::compiler
