// Expressions of section parameters on their own: which values are expressions, each operator,
// the sign rule for relative moves, units, exact fractions of a beat and the limits. Every
// expected text is worked out by hand from docs/language.md.
#include "compiler/frontend/param_expressions.hpp"

#include <gtest/gtest.h>

#include <string>

namespace seqc::compiler {
namespace {

const ParameterValues kValues{
    {"x", "100"},    {"neg", "-120"},         {"plus", "+40"}, {"a", "30"},
    {"b", "50"},     {"angle", "10deg"},      {"beat", "1b"},  {"half", "0.5s"},
    {"bar", "1bar"}, {"joint", "wrist_roll"}, {"zero", "0"},   {"third", "1/3b"}};

std::string value_of(const std::string& text) {
  const EvaluatedExpression e = evaluate_parameter_expression(text, kValues);
  EXPECT_TRUE(e.is_expression) << text;
  EXPECT_EQ(e.error, "") << text;
  return e.value;
}

std::string error_of(const std::string& text) {
  const EvaluatedExpression e = evaluate_parameter_expression(text, kValues);
  EXPECT_TRUE(e.is_expression) << text;
  return e.error;
}

TEST(ParamExpressions, ANameAloneOrSplicedWithLettersIsNoExpression) {
  for (const char* text : {"$x", "${x}", "${x}deg", "$x/s", "$joint", "${joint}_2", "x * 2", "500",
                           "$x.y", "${side}-arm", "+$joint", "-$joint"}) {
    EXPECT_FALSE(evaluate_parameter_expression(text, kValues).is_expression) << text;
  }
}

TEST(ParamExpressions, EachOperator) {
  EXPECT_EQ(value_of("$x * 2"), "200");
  EXPECT_EQ(value_of("2 * $x"), "200");
  EXPECT_EQ(value_of("$x / 2"), "50");
  EXPECT_EQ(value_of("$a + $b"), "80");
  EXPECT_EQ(value_of("$b - $a"), "20");
  EXPECT_EQ(value_of("$x+10"), "110");
  EXPECT_EQ(value_of("($a + $b) * 2"), "160");
  EXPECT_EQ(value_of("$a + $b * 2"), "130");
  EXPECT_EQ(value_of("${x} * 3"), "300");
  EXPECT_EQ(value_of("$angle + 5deg"), "15deg");
  EXPECT_EQ(value_of("$angle / 4"), "2.5deg");
  EXPECT_EQ(value_of("$angle / 3"), "3.333333deg");
}

TEST(ParamExpressions, ASignInFrontMakesARelativeMoveByTheWholeValue) {
  EXPECT_EQ(value_of("+$neg"), "-120");  // relative, by -120
  EXPECT_EQ(value_of("-$neg"), "+120");  // relative, by -(-120)
  EXPECT_EQ(value_of("+$x"), "+100");
  EXPECT_EQ(value_of("-$x"), "-100");
  EXPECT_EQ(value_of("+$plus"), "+40");
  EXPECT_EQ(value_of("-$x * 2"), "-200");
  EXPECT_EQ(value_of("-$x + 30"), "-70");
  EXPECT_EQ(value_of("-$angle"), "-10deg");
  EXPECT_EQ(value_of("+$zero"), "+0");
  EXPECT_EQ(value_of("($x)"), "100");  // no sign in front: absolute
  EXPECT_EQ(error_of("($neg)"),
            "'($neg)' comes out at -120 (device units), and an absolute position cannot be "
            "negative; begin it with + or - for a relative move");
  EXPECT_EQ(error_of("$a - $b"),
            "'$a - $b' comes out at -20 (device units), and an absolute position cannot be "
            "negative; begin it with + or - for a relative move");
}

TEST(ParamExpressions, UnitsMustAgree) {
  EXPECT_EQ(error_of("$x + 10deg"),
            "'$x + 10deg' cannot add 100 (device units) and 10deg: device units and degrees do "
            "not mix; write both in one unit");
  EXPECT_EQ(error_of("$x - $beat"),
            "'$x - $beat' cannot subtract 1b from 100 (device units): a time and a position do "
            "not add up");
  EXPECT_EQ(error_of("$half + $beat"),
            "'$half + $beat' cannot add 500ms and 1b: a beat's length in ms depends on the "
            "tempo; write both in one unit");
  EXPECT_EQ(error_of("$beat + $bar"),
            "'$beat + $bar' cannot add 1b and 1bar: a bar's length in beats depends on the "
            "meter; write both in one unit");
  EXPECT_EQ(error_of("$angle * $beat"),
            "'$angle * $beat' cannot multiply 10deg by 1b: at most one side may have a unit");
  EXPECT_EQ(error_of("$x / $angle"),
            "'$x / $angle' cannot divide 100 (device units) by 10deg: divide by a plain number");
  EXPECT_EQ(error_of("$joint * 2"),
            "'$joint * 2' uses $joint, which is 'wrist_roll', not a number such as 40, 10deg "
            "or 1b");
}

TEST(ParamExpressions, TimesAreExactFractions) {
  EXPECT_EQ(value_of("$beat / 3"), "1/3b");
  EXPECT_EQ(value_of("$beat * 2 / 3"), "2/3b");
  EXPECT_EQ(value_of("$beat / 2"), "0.5b");
  EXPECT_EQ(value_of("$third * 3"), "1b");
  EXPECT_EQ(value_of("$half * 3"), "1500ms");
  EXPECT_EQ(value_of("$half + 250ms"), "750ms");
  EXPECT_EQ(value_of("$bar / 6"), "1/6bar");
  EXPECT_EQ(value_of("$beat + 1/3b"), "4/3b");
  EXPECT_EQ(error_of("$half - 1s"), "'$half - 1s' comes out at -500ms; a time cannot be negative");
}

TEST(ParamExpressions, MistakesAndLimits) {
  EXPECT_EQ(error_of("$x / $zero"), "'$x / $zero' divides by zero");
  EXPECT_EQ(error_of("$x / 0"), "'$x / 0' divides by zero");
  EXPECT_EQ(error_of("$x / 3"),
            "'$x / 3' comes out at 100/3 (device units), not a whole number "
            "of device units");
  EXPECT_EQ(error_of("$x *"), "'$x *' ends where a value should follow");
  EXPECT_EQ(error_of("$x * * 2"), "'$x * * 2' has '*' where a value should be");
  EXPECT_EQ(error_of("($x + 1"), "'($x + 1' has a '(' that is never closed");
  EXPECT_EQ(error_of("$x + 1)"), "'$x + 1)' has a ')' that closes nothing");
  EXPECT_EQ(error_of("$x 2 + 1"), "'$x 2 + 1' has two values with no operator between them");
  EXPECT_EQ(error_of("$x * 1000000000 * 1000000000"),
            "'$x * 1000000000 * 1000000000' grows past any position or time (too large a value)");
  EXPECT_EQ(error_of("$x * 99999999999999999999"),
            "'$x * 99999999999999999999' has a number too large for any position or time");
  const std::string deep = std::string(17, '(') + "$x" + std::string(17, ')') + " * 2";
  EXPECT_EQ(error_of(deep), "'" + deep + "' nests more than 16 deep");
  const std::string negations = std::string(20, '-') + "$x";
  EXPECT_EQ(error_of(negations), "'" + negations + "' nests more than 16 deep");
  std::string longest = "$x";
  while (longest.size() < 201) longest += " + 1";
  EXPECT_EQ(error_of(longest), "an expression is at most 200 characters long; this one has " +
                                   std::to_string(longest.size()));
  // A huge value costs no more than a short one: reading stops at the limit.
  std::string huge = "$x";
  for (int i = 0; i < 200000; ++i) huge += "+1";
  EXPECT_EQ(error_of(huge), "an expression is at most 200 characters long; this one has 400002");
  const std::string parentheses = std::string(100000, '(') + "$x" + std::string(100000, ')');
  EXPECT_EQ(error_of(parentheses),
            "an expression is at most 200 characters long; this one has 200002");
}

TEST(ParamExpressions, UnknownNamesAreListed) {
  const EvaluatedExpression e = evaluate_parameter_expression("$x * $speed + $y", kValues);
  EXPECT_TRUE(e.is_expression);
  EXPECT_EQ(e.unknown, (std::vector<std::string>{"speed", "y"}));
}

}  // namespace
}  // namespace seqc::compiler
