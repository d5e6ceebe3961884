// Arithmetic on a section's parameters where a step uses them: `-$x`, `+$x`, `$x * 2`, `$beat / 3`,
// `$a + 10deg`, with parentheses. A value written as such an expression is worked out exactly
// (rational numbers, each with its unit: device units, degrees, ms, beats or bars) and written
// back as text the value parsers read: a position ("+120", "-60", "45.5deg") or a time ("250ms",
// "0.5b", "1/3b"). A value with a single `$name` or with `${name}` followed by letters is no
// expression: it is spliced as text, as sections always did, and so is `+$x` or `-$x` whose
// value is no number. Pure: no diagnostics here, the
// caller reports `error` at the value with the performance's values in a note.
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace seqc::compiler {

// Longest expression text and deepest nesting (parentheses and signs) read; past either the
// value is an error, found while reading it, so no input makes the reader recurse or work long.
inline constexpr std::size_t kMaxExpressionLength = 200;
inline constexpr int kMaxExpressionDepth = 16;

struct EvaluatedExpression {
  bool is_expression = false;  // false: `text` was no expression and is for splicing as before
  std::string value;           // the result as a position or time text (when no error)
  std::string error;           // what is wrong, for a diagnostic at the value (empty if none)
  std::vector<std::string> unknown;  // `$names` not among the parameters, in order written
};

// Parameter name -> the text of its value ("-120", "10deg", "1b", "wrist_roll").
using ParameterValues = std::map<std::string, std::string, std::less<>>;

// Works out `text` when it is an expression of parameters: it mentions a `$name` and an operator
// or parenthesis, and holds nothing but those, numbers with units and spaces.
//
// The rules: a bare number is device units when added to one and a plain factor when it scales
// one; units must agree to add (device units and degrees do not mix, nor times with positions,
// nor ms with beats or bars, which need the tempo); at most one side of `*` has a unit and the
// divisor of `/` has none. A position expression that begins with `+` or `-` is a relative move
// by its whole value (`+$x` with x = -120 moves by -120; `-$x` moves by -x); one that begins
// otherwise is absolute and must not come out negative. Device units come out whole; degrees
// as a decimal (to a millionth where they do not end); times as a decimal where one is exact,
// otherwise as `N/D` and the unit ("1/3b").
EvaluatedExpression evaluate_parameter_expression(std::string_view text,
                                                  const ParameterValues& values);

}  // namespace seqc::compiler
