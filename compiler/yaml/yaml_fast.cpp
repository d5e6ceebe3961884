// The fast path of the YAML loader. Why it exists: yaml-cpp's scanner matches a small regular
// expression tree per input character, which is nearly all of the time `seqc compile` spends on a
// large file. This reader handles only what it can be sure of and gives up on anything else,
// so correctness never depends on it covering much.
//
// yaml-cpp's marks that it reproduces (checked by the differential test): a block map starts at
// its first key, a block sequence (indentless ones too) at its first '-', a flow collection at
// its bracket, a scalar at its first character; a plain "null", "Null" or "NULL" is a null.
//
// Every parse function starts at a node's first character and ends at the first character of
// the next content line (or the end of the text), with that line's indent in next_indent_.
#include "compiler/yaml/yaml_fast.hpp"

namespace seqc::compiler::yaml_detail {
namespace {

struct NotInSubset {};

constexpr int kEof = -1;

// yaml-cpp refuses a key longer than 1024 characters ("illegal map value"); well below that,
// this reader leaves long keys to it.
constexpr std::size_t kMaxKeyLength = 1000;

bool is_alnum(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
}
// Characters a plain scalar of the subset may hold anywhere.
bool is_safe(char c) {
  return is_alnum(c) || c == '_' || c == '-' || c == '.' || c == '+' || c == '/';
}

class FastReader {
 public:
  FastReader(std::string_view s, std::size_t max_depth) : s_(s), max_depth_(max_depth) {}

  std::vector<FastEvent> run() {
    events_.reserve(s_.size() / 4);
    pos_ = 0;
    skip_to_content(/*at_line_start=*/true);
    if (next_indent_ != 0) fail();  // empty, or a root that does not start at column 0
    block_node(/*inline_value=*/false);
    if (next_indent_ != kEof) fail();
    return std::move(events_);
  }

 private:
  [[noreturn]] static void fail() { throw NotInSubset{}; }

  bool at_end() const { return pos_ >= s_.size(); }
  char peek(std::size_t ahead = 0) const {
    return pos_ + ahead < s_.size() ? s_[pos_ + ahead] : '\0';
  }
  std::uint32_t column() const { return static_cast<std::uint32_t>(pos_ - line_start_); }

  FastEvent mark(FastEvent::Kind kind) const {
    return FastEvent{kind, static_cast<std::uint32_t>(pos_), line_, column(), {}};
  }
  void push(FastEvent::Kind kind) { events_.push_back(FastEvent{kind, 0, 0, 0, {}}); }

  // To the end of a comment. Control characters other than a tab leave the subset: yaml-cpp
  // ends the stream at a NUL even inside a comment (found by the differential fuzzer).
  void skip_comment() {
    for (; !at_end() && s_[pos_] != '\n'; ++pos_) {
      const auto c = static_cast<unsigned char>(s_[pos_]);
      if (c < 0x20 && c != '\t') fail();
    }
  }

  void enter() {
    if (++depth_ > max_depth_) fail();
  }

  // From the end of a line (a '\n' or the end of the text), or from the very start: moves to the
  // first character of the next line holding something other than spaces and a comment.
  void skip_to_content(bool at_line_start = false) {
    for (;;) {
      if (!at_line_start) {
        if (at_end()) {
          next_indent_ = kEof;
          return;
        }
        ++pos_;  // the '\n'
        ++line_;
        line_start_ = pos_;
      }
      at_line_start = false;
      while (peek() == ' ') ++pos_;
      if (at_end()) {
        next_indent_ = kEof;
        return;
      }
      const char c = s_[pos_];
      if (c == '\n') continue;
      if (c == '#') {  // at the start of a line or after spaces: a comment line
        skip_comment();
        continue;
      }
      next_indent_ = static_cast<int>(column());
      if (next_indent_ == 0 && (s_.substr(pos_, 3) == "---" || s_.substr(pos_, 3) == "...")) {
        fail();  // document markers
      }
      return;
    }
  }

  // After a node that ends its line: only spaces and a comment may follow.
  void finish_line() {
    const std::size_t start = pos_;
    while (peek() == ' ') ++pos_;
    if (at_end() || s_[pos_] == '\n') return;
    if (s_[pos_] == '#' && pos_ > start) {
      skip_comment();
      return;
    }
    fail();
  }

  bool dash_entry() const {  // "- ", "-\n" or "-" at the end of the text
    const char next = peek(1);
    return peek() == '-' && (next == ' ' || next == '\n' || next == '\0');
  }

  // A plain scalar at pos_: returns it and leaves pos_ after its last character. Inner runs of
  // spaces are part of it when another scalar character follows.
  std::string_view scalar() {
    const char c = peek();
    const bool sign = c == '-' || c == '+';
    if (!(is_alnum(c) || c == '_' || c == '.' || c == '/' || (sign && is_safe(peek(1))))) fail();
    const std::size_t start = pos_;
    for (;;) {
      while (pos_ < s_.size() && is_safe(s_[pos_])) ++pos_;
      std::size_t after = pos_;
      while (after < s_.size() && s_[after] == ' ') ++after;
      if (after == pos_ || after >= s_.size() || !is_safe(s_[after])) break;
      pos_ = after;
    }
    return s_.substr(start, pos_ - start);
  }

  void emit_scalar(const FastEvent& at, std::string_view value) {
    FastEvent e = at;
    if (value == "null" || value == "Null" || value == "NULL") {
      e.kind = FastEvent::Kind::Null;
    } else {
      e.value = value;
    }
    events_.push_back(e);
  }

  // True if a "key:" (the colon followed by a space or the end of the line) is at pos_, which
  // is just after a scalar.
  bool key_colon() const {
    const char next = peek(1);
    return peek() == ':' && (next == ' ' || next == '\n' || next == '\0');
  }

  // A node at pos_ in block context, on its own line or after "- ". With inline_value (after
  // "key: "), only a scalar or a flow collection may follow on the line.
  void block_node(bool inline_value) {
    const char c = peek();
    if (c == '{' || c == '[') {
      flow_node();
      finish_line();
      skip_to_content();
      return;
    }
    if (dash_entry()) {
      if (inline_value) fail();
      block_sequence(column(), /*indentless=*/false);
      return;
    }
    const FastEvent at = mark(FastEvent::Kind::Scalar);
    const std::string_view value = scalar();
    if (key_colon()) {
      if (inline_value || value.size() > kMaxKeyLength) fail();
      block_map(at, value);
      return;
    }
    emit_scalar(at, value);
    finish_line();
    skip_to_content();
  }

  // The value after "key:" or "- ": on the same line, or on the following lines.
  void block_value(std::uint32_t indent, bool after_dash) {
    const std::size_t start = pos_;
    while (peek() == ' ') ++pos_;
    if (!at_end() && s_[pos_] != '\n' && s_[pos_] != '#') {
      block_node(/*inline_value=*/!after_dash);
      return;
    }
    pos_ = start;
    finish_line();
    skip_to_content();
    if (next_indent_ > static_cast<int>(indent)) {
      block_node(/*inline_value=*/false);
    } else if (!after_dash && next_indent_ == static_cast<int>(indent) && dash_entry()) {
      block_sequence(indent, /*indentless=*/true);
    } else {
      fail();  // an empty value (a null)
    }
  }

  // A block map whose first key (already read, at `first`) ends at pos_, on its ':'.
  void block_map(const FastEvent& first, std::string_view first_key) {
    enter();
    const std::uint32_t indent = first.column;
    FastEvent start = first;
    start.kind = FastEvent::Kind::MapStart;
    events_.push_back(start);
    FastEvent at = first;
    std::string_view key = first_key;
    for (;;) {
      emit_scalar(at, key);
      ++pos_;  // the ':'
      block_value(indent, /*after_dash=*/false);
      if (next_indent_ < static_cast<int>(indent)) break;
      if (next_indent_ > static_cast<int>(indent)) fail();
      at = mark(FastEvent::Kind::Scalar);
      key = scalar();
      if (!key_colon() || key.size() > kMaxKeyLength) fail();
    }
    push(FastEvent::Kind::MapEnd);
    --depth_;
  }

  // A block sequence whose first "-" is at pos_, in column `indent`. An indentless sequence is
  // a map's value at the map's own indent; it ends at the map's next key.
  void block_sequence(std::uint32_t indent, bool indentless) {
    enter();
    events_.push_back(mark(FastEvent::Kind::SeqStart));
    for (;;) {
      ++pos_;  // the '-'
      block_value(indent, /*after_dash=*/true);
      if (next_indent_ < static_cast<int>(indent)) break;
      if (next_indent_ > static_cast<int>(indent)) fail();
      if (!dash_entry()) {
        if (indentless) break;
        fail();
      }
    }
    push(FastEvent::Kind::SeqEnd);
    --depth_;
  }

  // ---- flow collections, on one line ---------------------------------------------------------

  void skip_spaces() {
    while (peek() == ' ') ++pos_;
  }

  void flow_node() {
    const char c = peek();
    if (c == '{') {
      flow_map();
    } else if (c == '[') {
      flow_sequence();
    } else {
      const FastEvent at = mark(FastEvent::Kind::Scalar);
      const std::string_view value = scalar();
      if (peek() == ':') fail();  // a single-pair map, or a ':' inside the scalar
      emit_scalar(at, value);
    }
  }

  void flow_map() {
    enter();
    events_.push_back(mark(FastEvent::Kind::MapStart));
    ++pos_;
    skip_spaces();
    if (peek() != '}') {
      for (;;) {
        const FastEvent at = mark(FastEvent::Kind::Scalar);
        const std::string_view key = scalar();
        if (peek() != ':' || peek(1) != ' ' || key.size() > kMaxKeyLength) fail();
        emit_scalar(at, key);
        pos_ += 2;
        skip_spaces();
        flow_node();
        if (!another_flow_item('}')) break;
      }
    }
    ++pos_;
    push(FastEvent::Kind::MapEnd);
    --depth_;
  }

  void flow_sequence() {
    enter();
    events_.push_back(mark(FastEvent::Kind::SeqStart));
    ++pos_;
    skip_spaces();
    if (peek() != ']') {
      for (;;) {
        flow_node();
        if (!another_flow_item(']')) break;
      }
    }
    ++pos_;
    push(FastEvent::Kind::SeqEnd);
    --depth_;
  }

  // After a flow item: past a ',' (true: another item follows) or at `close` (false).
  bool another_flow_item(char close) {
    skip_spaces();
    if (peek() == ',') {
      ++pos_;
      skip_spaces();
      return true;
    }
    if (peek() != close) fail();
    return false;
  }

  std::string_view s_;
  std::size_t max_depth_;
  std::size_t pos_ = 0;
  std::size_t line_start_ = 0;
  std::uint32_t line_ = 0;
  int next_indent_ = kEof;
  std::size_t depth_ = 0;
  std::vector<FastEvent> events_;
};

}  // namespace

std::optional<std::vector<FastEvent>> fast_events(std::string_view text, std::size_t max_depth) {
  if (text.size() > UINT32_MAX) return std::nullopt;
  try {
    return FastReader(text, max_depth).run();
  } catch (const NotInSubset&) {
    return std::nullopt;
  }
}

}  // namespace seqc::compiler::yaml_detail
