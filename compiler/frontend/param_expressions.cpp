// Parameter expressions (param_expressions.hpp): read into tokens, parsed by recursive descent
// with a depth count, and worked out on exact fractions whose numerator and denominator stay
// below kLimit (past it the value is an error, never a wrapped integer).
#include "compiler/frontend/param_expressions.hpp"

#include <cctype>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <utility>

namespace seqc::compiler {
namespace {

__extension__ typedef __int128 Wide;

// Far beyond any position, angle or time a file can hold, and well inside 64 bits.
constexpr std::int64_t kLimit = 1'000'000'000'000'000;

struct Ratio {
  std::int64_t num = 0;
  std::int64_t den = 1;
};

// num/den reduced with a positive denominator; nullopt when either part passes kLimit or the
// denominator is zero.
std::optional<Ratio> make_ratio(Wide num, Wide den) {
  if (den == 0) return std::nullopt;
  if (den < 0) {
    num = -num;
    den = -den;
  }
  Wide a = num < 0 ? -num : num, b = den;
  while (b != 0) {
    const Wide t = a % b;
    a = b;
    b = t;
  }
  if (a > 1) {
    num /= a;
    den /= a;
  }
  if (num > kLimit || num < -kLimit || den > kLimit) return std::nullopt;
  return Ratio{static_cast<std::int64_t>(num), static_cast<std::int64_t>(den)};
}

enum class Unit { Number, Degrees, Ms, Beats, Bars };

struct Quantity {
  Ratio value;
  Unit unit = Unit::Number;
};

bool name_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_'; }
bool digit(char c) { return c >= '0' && c <= '9'; }

// The decimal digits of r when it ends within 9 places ("0.5", "-12.25"); nullopt otherwise.
std::optional<std::string> exact_decimal(Ratio r) {
  std::int64_t den = r.den;
  int twos = 0, fives = 0;
  while (den % 2 == 0) den /= 2, ++twos;
  while (den % 5 == 0) den /= 5, ++fives;
  const int places = twos > fives ? twos : fives;
  if (den != 1 || places > 9) return std::nullopt;
  const bool negative = r.num < 0;
  Wide scaled = static_cast<Wide>(negative ? -r.num : r.num);
  for (int i = 0; i < places; ++i) scaled *= 10;
  scaled /= r.den;
  std::string digits;
  do {
    digits.insert(digits.begin(), static_cast<char>('0' + static_cast<int>(scaled % 10)));
    scaled /= 10;
  } while (scaled != 0);
  if (places > 0) {
    if (digits.size() <= static_cast<std::size_t>(places)) {
      digits.insert(0, static_cast<std::size_t>(places) + 1 - digits.size(), '0');
    }
    digits.insert(digits.size() - static_cast<std::size_t>(places), ".");
  }
  return (negative ? "-" : "") + digits;
}

// "12", "0.5", "1/3": exact, as the time parser reads it.
std::string ratio_text(Ratio r) {
  if (auto d = exact_decimal(r)) return *d;
  return std::to_string(r.num) + "/" + std::to_string(r.den);
}

std::string_view unit_suffix(Unit u) {
  switch (u) {
    case Unit::Number:
      return "";
    case Unit::Degrees:
      return "deg";
    case Unit::Ms:
      return "ms";
    case Unit::Beats:
      return "b";
    case Unit::Bars:
      return "bar";
  }
  return "";
}

// A quantity for messages: "100 (device units)", "10deg", "1/3b".
std::string describe(const Quantity& q) {
  if (q.unit == Unit::Number) return ratio_text(q.value) + " (device units)";
  return ratio_text(q.value) + std::string(unit_suffix(q.unit));
}

bool is_time(Unit u) { return u == Unit::Ms || u == Unit::Beats || u == Unit::Bars; }

// A number with its unit at `text[i]`: digits, a decimal part, a `/digits` fraction, then a
// unit not followed by a letter. Advances `i` past it; nullopt (with `i` unchanged) when there
// is none. `too_large` is set for digits past kLimit.
std::optional<Quantity> read_number(std::string_view text, std::size_t& i, bool& too_large) {
  std::size_t j = i;
  if (j >= text.size() || !digit(text[j])) return std::nullopt;
  Wide num = 0, den = 1;
  for (; j < text.size() && digit(text[j]); ++j) {
    num = num * 10 + (text[j] - '0');
    if (num > kLimit) too_large = true, num = kLimit;
  }
  if (j + 1 < text.size() && text[j] == '.' && digit(text[j + 1])) {
    for (++j; j < text.size() && digit(text[j]); ++j) {
      if (den < kLimit) {
        num = num * 10 + (text[j] - '0');
        den *= 10;
      }
      if (num > kLimit) too_large = true, num = kLimit;
    }
  }
  if (j + 1 < text.size() && text[j] == '/' && digit(text[j + 1])) {
    Wide d = 0;
    for (++j; j < text.size() && digit(text[j]); ++j) {
      d = d * 10 + (text[j] - '0');
      if (d > kLimit) too_large = true, d = kLimit;
    }
    den *= d;  // a zero denominator is the caller's division by zero
    if (den > kLimit) too_large = true;
  }
  Unit unit = Unit::Number;
  for (auto [suffix, u] : {std::pair<std::string_view, Unit>{"bars", Unit::Bars},
                           {"bar", Unit::Bars},
                           {"deg", Unit::Degrees},
                           {"ms", Unit::Ms},
                           {"s", Unit::Ms},
                           {"b", Unit::Beats}}) {
    if (text.substr(j, suffix.size()) == suffix) {
      if (suffix == "s") num *= 1000;
      unit = u;
      j += suffix.size();
      break;
    }
  }
  if (j < text.size() && name_char(text[j])) return std::nullopt;
  i = j;
  Quantity q;
  q.unit = unit;
  if (den == 0) {
    q.value = Ratio{0, 0};  // marks a written zero denominator
  } else if (auto r = make_ratio(num, den)) {
    q.value = *r;
  } else {
    too_large = true;
  }
  return q;
}

struct Token {
  enum class Kind { Number, Parameter, Operator, Open, Close };
  Kind kind = Kind::Number;
  Quantity number;
  std::string name;
  char op = 0;
};

Token token(Token::Kind kind, Quantity number = {}, std::string name = {}, char op = 0) {
  Token t;
  t.kind = kind;
  t.number = number;
  t.name = std::move(name);
  t.op = op;
  return t;
}

// `text` as tokens; nullopt when it holds anything an expression cannot (a word, a stray `$`).
// Reading stops after kMaxExpressionLength tokens, setting `cut` (a longer text is too long
// anyway), so a huge value costs no more than a short one.
std::optional<std::vector<Token>> tokens_of(std::string_view text, bool& too_large, bool& cut) {
  std::vector<Token> out;
  for (std::size_t i = 0; i < text.size();) {
    if (out.size() > kMaxExpressionLength) {
      cut = true;
      break;
    }
    const char c = text[i];
    if (c == ' ' || c == '\t') {
      ++i;
    } else if (c == '$') {
      const bool braced = i + 1 < text.size() && text[i + 1] == '{';
      std::size_t from = i + (braced ? 2 : 1), to = from;
      while (to < text.size() && name_char(text[to])) ++to;
      if (to == from || (braced && (to >= text.size() || text[to] != '}'))) return std::nullopt;
      if (!braced && to < text.size() && text[to] == '{') return std::nullopt;
      out.push_back(token(Token::Kind::Parameter, {}, std::string(text.substr(from, to - from))));
      i = to + (braced ? 1 : 0);
      if (braced && i < text.size() && name_char(text[i])) return std::nullopt;  // ${a}deg
    } else if (c == '+' || c == '-' || c == '*' || c == '/') {
      out.push_back(token(Token::Kind::Operator, {}, {}, c));
      ++i;
    } else if (c == '(' || c == ')') {
      out.push_back(token(c == '(' ? Token::Kind::Open : Token::Kind::Close));
      ++i;
    } else if (auto q = read_number(text, i, too_large)) {
      out.push_back(token(Token::Kind::Number, *q));
    } else {
      return std::nullopt;
    }
  }
  return out;
}

// A parameter's value as a quantity: an optional sign, then a number with its unit.
std::optional<Quantity> value_quantity(std::string_view text, bool& too_large) {
  bool negative = false;
  if (!text.empty() && (text[0] == '+' || text[0] == '-')) {
    negative = text[0] == '-';
    text.remove_prefix(1);
  }
  std::size_t i = 0;
  auto q = read_number(text, i, too_large);
  if (!q || i != text.size()) return std::nullopt;
  if (negative) q->value.num = -q->value.num;
  return q;
}

class Parser {
 public:
  Parser(std::string_view text, const std::vector<Token>& tokens, const ParameterValues& values)
      : text_(text), tokens_(tokens), values_(values) {}

  std::optional<Quantity> parse() {
    auto q = expression(0);
    if (q && at_ < tokens_.size()) {
      return fail(tokens_[at_].kind == Token::Kind::Close
                      ? "has a ')' that closes nothing"
                      : "has two values with no operator between them");
    }
    return q;
  }
  const std::string& error() const { return error_; }

 private:
  std::optional<Quantity> fail(const std::string& why) {
    if (error_.empty()) error_ = "'" + std::string(text_) + "' " + why;
    return std::nullopt;
  }
  bool next_is(char op) const {
    return at_ < tokens_.size() && tokens_[at_].kind == Token::Kind::Operator &&
           tokens_[at_].op == op;
  }

  std::optional<Quantity> expression(int depth) {
    auto left = term(depth);
    while (left && (next_is('+') || next_is('-'))) {
      const char op = tokens_[at_++].op;
      auto right = term(depth);
      if (!right) return std::nullopt;
      left = add(*left, *right, op == '-');
    }
    return left;
  }

  std::optional<Quantity> term(int depth) {
    auto left = unary(depth);
    while (left && (next_is('*') || next_is('/'))) {
      const char op = tokens_[at_++].op;
      auto right = unary(depth);
      if (!right) return std::nullopt;
      left = op == '*' ? multiply(*left, *right) : divide(*left, *right);
    }
    return left;
  }

  std::optional<Quantity> unary(int depth) {
    if (depth > kMaxExpressionDepth) {
      return fail("nests more than " + std::to_string(kMaxExpressionDepth) + " deep");
    }
    if (next_is('+') || next_is('-')) {
      const bool minus = tokens_[at_++].op == '-';
      auto q = unary(depth + 1);
      if (q && minus) q->value.num = -q->value.num;
      return q;
    }
    return primary(depth);
  }

  std::optional<Quantity> primary(int depth) {
    if (at_ >= tokens_.size()) return fail("ends where a value should follow");
    const Token& t = tokens_[at_++];
    switch (t.kind) {
      case Token::Kind::Number:
        if (t.number.value.den == 0) return fail("divides by zero");
        return t.number;
      case Token::Kind::Parameter: {
        const std::string& written = values_.find(t.name)->second;
        bool too_large = false;
        auto q = value_quantity(written, too_large);
        if (too_large) return fail("uses $" + t.name + " = " + written + ", too large a value");
        if (!q || q->value.den == 0) {
          return fail("uses $" + t.name + ", which is '" + written +
                      "', not a number such as 40, 10deg or 1b");
        }
        return q;
      }
      case Token::Kind::Open: {
        auto q = expression(depth + 1);
        if (!q) return std::nullopt;
        if (at_ >= tokens_.size() || tokens_[at_].kind != Token::Kind::Close) {
          return fail("has a '(' that is never closed");
        }
        ++at_;
        return q;
      }
      case Token::Kind::Close:
        return fail("has a ')' where a value should be");
      case Token::Kind::Operator:
        break;
    }
    return fail("has '" + std::string(1, t.op) + "' where a value should be");
  }

  std::optional<Quantity> add(const Quantity& a, const Quantity& b, bool subtract) {
    if (a.unit != b.unit) {
      const std::string what = subtract ? "cannot subtract " + describe(b) + " from " + describe(a)
                                        : "cannot add " + describe(a) + " and " + describe(b);
      std::string why;
      if (is_time(a.unit) != is_time(b.unit)) {
        why = "a time and a position do not add up";
      } else if (!is_time(a.unit)) {
        why = "device units and degrees do not mix; write both in one unit";
      } else if (a.unit == Unit::Ms || b.unit == Unit::Ms) {
        why = "a beat's length in ms depends on the tempo; write both in one unit";
      } else {
        why = "a bar's length in beats depends on the meter; write both in one unit";
      }
      return fail(what + ": " + why);
    }
    const Wide n = static_cast<Wide>(a.value.num) * b.value.den +
                   (subtract ? -1 : 1) * static_cast<Wide>(b.value.num) * a.value.den;
    return checked(make_ratio(n, static_cast<Wide>(a.value.den) * b.value.den), a.unit);
  }

  std::optional<Quantity> multiply(const Quantity& a, const Quantity& b) {
    if (a.unit != Unit::Number && b.unit != Unit::Number) {
      return fail("cannot multiply " + describe(a) + " by " + describe(b) +
                  ": at most one side may have a unit");
    }
    return checked(make_ratio(static_cast<Wide>(a.value.num) * b.value.num,
                              static_cast<Wide>(a.value.den) * b.value.den),
                   a.unit == Unit::Number ? b.unit : a.unit);
  }

  std::optional<Quantity> divide(const Quantity& a, const Quantity& b) {
    if (b.unit != Unit::Number) {
      return fail("cannot divide " + describe(a) + " by " + describe(b) +
                  ": divide by a plain number");
    }
    if (b.value.num == 0) return fail("divides by zero");
    return checked(make_ratio(static_cast<Wide>(a.value.num) * b.value.den,
                              static_cast<Wide>(a.value.den) * b.value.num),
                   a.unit);
  }

  std::optional<Quantity> checked(std::optional<Ratio> r, Unit unit) {
    if (!r) return fail("grows past any position or time (too large a value)");
    return Quantity{*r, unit};
  }

  std::string_view text_;
  const std::vector<Token>& tokens_;
  const ParameterValues& values_;
  std::size_t at_ = 0;
  std::string error_;
};

// The result as the value parsers read it, or an error in `out`.
void write_result(std::string_view text, const Quantity& q, bool signed_start,
                  EvaluatedExpression& out) {
  const std::string quoted = "'" + std::string(text) + "'";
  const std::string suffix(unit_suffix(q.unit));
  const bool negative = q.value.num < 0;
  if (is_time(q.unit)) {
    if (negative) {
      out.error = quoted + " comes out at " + describe(q) + "; a time cannot be negative";
      return;
    }
    out.value = ratio_text(q.value) + suffix;
    return;
  }
  if (negative && !signed_start) {
    out.error = quoted + " comes out at " + describe(q) +
                ", and an absolute position cannot be negative; begin it with + or - for a "
                "relative move";
    return;
  }
  Ratio magnitude{negative ? -q.value.num : q.value.num, q.value.den};
  std::string digits;
  if (q.unit == Unit::Number) {
    if (magnitude.den != 1) {
      out.error = quoted + " comes out at " + describe(q) + ", not a whole number of device units";
      return;
    }
    digits = std::to_string(magnitude.num);
  } else if (auto d = exact_decimal(magnitude)) {
    digits = *d;
  } else {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.6f",
                  static_cast<double>(magnitude.num) / static_cast<double>(magnitude.den));
    digits = buf;
    while (digits.back() == '0') digits.pop_back();
    if (digits.back() == '.') digits.pop_back();
  }
  out.value = (signed_start ? (negative ? "-" : "+") : "") + digits + suffix;
}

}  // namespace

EvaluatedExpression evaluate_parameter_expression(std::string_view text,
                                                  const ParameterValues& values) {
  EvaluatedExpression out;
  bool too_large = false, cut = false;
  auto tokens = tokens_of(text, too_large, cut);
  if (!tokens) return out;
  bool parameter = false, operation = false;
  for (const Token& t : *tokens) {
    if (t.kind == Token::Kind::Parameter) parameter = true;
    if (t.kind != Token::Kind::Parameter && t.kind != Token::Kind::Number) operation = true;
  }
  // A text cut short holds nothing but what expressions hold as far as it was read; past the
  // length limit it is an expression (too long) when it mentions a parameter at all.
  const bool expression = cut ? text.find('$') != std::string_view::npos : parameter && operation;
  if (!expression) return out;
  out.is_expression = true;
  if (text.size() > kMaxExpressionLength) {
    out.error = "an expression is at most " + std::to_string(kMaxExpressionLength) +
                " characters long; this one has " + std::to_string(text.size());
    return out;
  }
  for (const Token& t : *tokens) {
    if (t.kind == Token::Kind::Parameter && values.find(t.name) == values.end()) {
      out.unknown.push_back(t.name);
    }
  }
  if (!out.unknown.empty()) return out;
  if (tokens->size() == 2 && tokens->front().kind == Token::Kind::Operator &&
      tokens->back().kind == Token::Kind::Parameter) {
    // `+$x` and `-$x` with a value that is no number (`+$joint`) stay text, as they always were:
    // the parser of what stands there says what is wrong with it.
    bool ignored = false;
    if (!value_quantity(values.find(tokens->back().name)->second, ignored)) return {};
  }
  if (too_large) {
    out.error = "'" + std::string(text) + "' has a number too large for any position or time";
    return out;
  }
  Parser parser(text, *tokens, values);
  auto q = parser.parse();
  if (!q) {
    out.error = parser.error();
    return out;
  }
  const bool signed_start = tokens->front().kind == Token::Kind::Operator &&
                            (tokens->front().op == '+' || tokens->front().op == '-');
  write_result(text, *q, signed_start, out);
  return out;
}

}  // namespace seqc::compiler
