// `path: line` tip moves on the xArm: the compiled actions, sampled at every millisecond as the
// controller moves them (each servo in a straight line from its previous target to the new one
// over the action's time), keep the tip within the tolerance of the straight line, by forward
// kinematics written out here from the documented conventions (not the compiler's); and the
// lines it refuses, with where along the line.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <iostream>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "tests/compiler/lang_test_util.hpp"
#include "tests/compiler/xarm_reference.hpp"

namespace seqc::compiler {
namespace {

using testing::compile_text;
using testing::distance;
using testing::kDegPerUnit;
using testing::messages;
using testing::program_of;

// The xArm profile: kDegPerUnit (0.24) degrees per unit; links 72 (table to shoulder), 97, 96
// and 150 mm; every joint's zero at 500, the base (id 6) turning +1, shoulder 5, elbow 4, wrist
// 3 -1.

using Vec = std::array<double, 3>;

Vec forward(const std::map<int, double>& pos) {
  const double rad = kDegPerUnit * std::numbers::pi / 180;
  const double base = (pos.at(6) - 500) * rad;
  const double s = -(pos.at(5) - 500) * rad;
  const double e = -(pos.at(4) - 500) * rad;
  const double w = -(pos.at(3) - 500) * rad;
  const double r = 97 * std::sin(s) + 96 * std::sin(s + e) + 150 * std::sin(s + e + w);
  const double z = 72 + 97 * std::cos(s) + 96 * std::cos(s + e) + 150 * std::cos(s + e + w);
  return {r * std::cos(base), r * std::sin(base), z};
}

// Every servo's position at millisecond t as the controller moves it: from its previous target
// to the action's target in a straight line over the action's time.
struct Sampler {
  explicit Sampler(const ServoProgram& p) : program(p) {}
  std::map<int, double> at(std::uint32_t t) const {
    std::map<int, double> target, pos;
    for (const Keyframe& k : program.keyframes) {
      if (k.start_ms >= t) break;
      const double f = std::min(1.0, static_cast<double>(t - k.start_ms) / k.time_ms);
      for (const auto& s : k.targets) {
        const double from = target.count(s.id) ? target[s.id] : s.position;
        pos[s.id] = from + (s.position - from) * f;
        target[s.id] = s.position;
      }
    }
    return pos;
  }
  std::size_t actions_between(std::uint32_t a, std::uint32_t b) const {
    std::size_t n = 0;
    for (const Keyframe& k : program.keyframes) n += k.start_ms >= a && k.start_ms < b;
    return n;
  }
  const ServoProgram& program;
};

double quad_in_out(double t) { return t < 0.5 ? 2 * t * t : 1 - 2 * (1 - t) * (1 - t); }

struct LineCheck {
  double worst = 0;
  std::uint32_t worst_at = 0;
  std::size_t actions = 0;
};

// The tip against the line from where it is at `a` to `to`, eased by `ease`, every millisecond.
template <typename Ease>
LineCheck check_line(const ServoProgram& p, std::uint32_t a, std::uint32_t b, const Vec& to,
                     Ease ease) {
  const Sampler s(p);
  const Vec from = forward(s.at(a));
  LineCheck c;
  for (std::uint32_t t = a; t <= b; ++t) {
    const double f = ease(static_cast<double>(t - a) / (b - a));
    const Vec want = {from[0] + (to[0] - from[0]) * f, from[1] + (to[1] - from[1]) * f,
                      from[2] + (to[2] - from[2]) * f};
    const double d = distance(forward(s.at(t)), want);
    if (d > c.worst) c.worst = d, c.worst_at = t;
  }
  c.actions = s.actions_between(a, b);
  return c;
}

constexpr const char* kStart = R"(robot: xarm
sequence:
  - move: home
    time: 1s
  - move: {tip: [200mm, 0mm, 120mm], pitch: 135deg, claw: 300}
    time: 1s
)";

TEST(TipLine, EasedLineIsFollowedWithinTheDefaultMillimetreEveryMillisecond) {
  const auto out =
      compile_text(std::string(kStart) + R"(  - move: {tip: [200mm, 100mm, 60mm], claw: 600}
    time: 1s
    path: line
    ease: in-out
)");
  ASSERT_TRUE(messages(out).empty()) << ::testing::PrintToString(messages(out));
  const ServoProgram& p = program_of(out);
  const LineCheck c = check_line(p, 2000, 3000, {200, 100, 60}, quad_in_out);
  std::cout << "line 1 mm: worst " << c.worst << " mm at " << c.worst_at << " ms, " << c.actions
            << " actions\n";
  EXPECT_LE(c.worst, 1.0 + 1e-9);
  // The program carries the same largest distance for `seqc check`; with no line it has none.
  ASSERT_TRUE(p.tip_error_mm.has_value());
  EXPECT_NEAR(*p.tip_error_mm, c.worst, 1e-9);
  EXPECT_EQ(p.tip_error_at_ms, c.worst_at);
  EXPECT_FALSE(program_of(compile_text(kStart)).tip_error_mm.has_value());
  // The claw follows its own quad in-out from 300 to 600 within its 1 unit.
  const Sampler s(p);
  for (std::uint32_t t = 2000; t <= 3000; ++t) {
    EXPECT_NEAR(s.at(t).at(1), 300 + 300 * quad_in_out((t - 2000) / 1000.0), 1.0 + 1e-9) << t;
  }
  // A straight joint move cannot do it: the tip would bow away from the line (the joints' own
  // curves), which is why the line needs several actions.
  EXPECT_GT(c.actions, 1u);
  // Every action lasts at least the controller's 20 ms.
  for (const Keyframe& k : p.keyframes) EXPECT_GE(k.time_ms, 20);
}

// Another track's segment boundaries inside a line (a claw in two 500 ms moves, a wrist roll in
// 300 ms moves) are action boundaries for every servo, the joints included, and another track's
// curve (a claw eased in two moves) is fitted with actions of its own: in both, the tip must
// stay within the tolerance at every millisecond, whichever track is walked first.
TEST(TipLine, AnotherTracksBoundariesInsideTheLineKeepTheTipOnIt) {
  const std::string line_track = R"(      arm:
        - move: {tip: [200mm, 100mm, 60mm]}
          time: 1s
          path: line
          ease: in-out
)";
  const std::string hand_track = R"(      hand:
        - move: {claw: 500}
          time: 500ms
        - move: {claw: 650}
          time: 500ms
)";
  const std::string roll_track = R"(      roll:
        - move: {wrist_roll: 600}
          time: 300ms
        - move: {wrist_roll: 400}
          time: 300ms
        - move: {wrist_roll: 550}
          time: 300ms
)";
  const std::string eased_track = R"(      hand:
        - move: {claw: 500}
          time: 600ms
          ease: in-out
        - move: {claw: 650}
          time: 400ms
          ease: out
)";
  // Each file, the other track's servo (by id) and where its moves put it u ms into the line.
  struct Case {
    std::string text;
    int id;
    std::function<double(double)> want;
  };
  auto claw_steps = [](double u) {
    return u <= 500 ? 300 + 200 * u / 500 : 500 + 150 * (u - 500) / 500;
  };
  auto roll_steps = [](double u) {
    return u <= 300   ? 500 + 100 * u / 300
           : u <= 600 ? 600 - 200 * (u - 300) / 300
           : u <= 900 ? 400 + 150 * (u - 600) / 300
                      : 550;
  };
  auto claw_eased = [](double u) {
    const double out = 1 - (1 - (u - 600) / 400) * (1 - (u - 600) / 400);  // quad-out
    return u <= 600 ? 300 + 200 * quad_in_out(u / 600) : 500 + 150 * out;
  };
  const Case cases[] = {
      {std::string(kStart) + "  - together:\n" + line_track + hand_track, 1, claw_steps},
      {std::string(kStart) + "  - together:\n" + hand_track + line_track, 1, claw_steps},
      {std::string(kStart) + "  - together:\n" + line_track + roll_track, 2, roll_steps},
      {std::string(kStart) + "  - together:\n" + line_track + eased_track, 1, claw_eased},
      {std::string(kStart) + "  - together:\n" + eased_track + line_track, 1, claw_eased},
  };
  for (const Case& k : cases) {
    const auto out = compile_text(k.text);
    ASSERT_TRUE(messages(out).empty()) << ::testing::PrintToString(messages(out));
    const ServoProgram& p = program_of(out);
    const LineCheck c = check_line(p, 2000, 3000, {200, 100, 60}, quad_in_out);
    std::cout << "line beside another track: worst " << c.worst << " mm at " << c.worst_at
              << " ms, " << c.actions << " actions\n";
    EXPECT_LE(c.worst, 1.0 + 1e-9) << k.text;
    // What `seqc check` prints as the tip's fit is this same largest distance.
    ASSERT_TRUE(p.tip_error_mm.has_value());
    EXPECT_NEAR(*p.tip_error_mm, c.worst, 1e-9);
    EXPECT_EQ(p.tip_error_at_ms, c.worst_at);
    // The other track's servo still follows its own moves within its unit.
    const Sampler s(p);
    for (std::uint32_t t = 2000; t <= 3000; ++t) {
      EXPECT_NEAR(s.at(t).at(k.id), k.want(t - 2000.0), 1.0 + 1e-9) << t << "\n" << k.text;
    }
  }
}

// Searched again for another track's boundaries, a line's joints move in other pieces: the
// fastest of them is still held to each joint's max_speed. The speed each joint reaches is
// measured here from the actions (target to target, over the action's time); with max_speed
// just under it, the line's step must be warned about ("... above elbow's 310/s").
TEST(TipLine, ALineSearchedAgainKeepsItsJointsMaxSpeed) {
  const std::string tracks = R"(  - together:
      arm:
        - move: {tip: [200mm, 100mm, 60mm]}
          time: 1s
          path: line
          ease: in-out
      hand:
        - move: {claw: 500}
          time: 500ms
        - move: {claw: 650}
          time: 500ms
)";
  const std::pair<const char*, int> joints[] = {
      {"wrist_pitch", 3}, {"elbow", 4}, {"shoulder", 5}, {"base", 6}};
  const auto free_run = compile_text(std::string(kStart) + tracks);
  ASSERT_TRUE(messages(free_run).empty()) << ::testing::PrintToString(messages(free_run));
  std::map<int, double> fastest;  // units/s over the line's actions, by id
  std::map<int, int> last;
  for (const Keyframe& k : program_of(free_run).keyframes) {
    for (const auto& t : k.targets) {
      if (k.start_ms >= 2000 && k.start_ms < 3000 && last.count(t.id) != 0) {
        const double v = std::abs(t.position - last[t.id]) * 1000.0 / k.time_ms;
        fastest[t.id] = std::max(fastest[t.id], v);
      }
      last[t.id] = t.position;
    }
  }
  for (const auto& [name, id] : joints) {
    ASSERT_GT(fastest[id], 1) << name;
    std::string robot = "robot:\n  profile: xarm\n  servos:\n";
    robot += "    " + std::string(name) + ": {id: " + std::to_string(id) +
             ", max_speed: " + std::to_string(fastest[id] - 0.5) + "/s}\n";
    std::string text = std::string(kStart) + tracks;
    text.replace(0, std::string("robot: xarm\n").size(), robot);
    const auto out = compile_text(text);
    // The line's step is on line 12 with this robot section (three lines longer than kStart's).
    bool warned = false;
    for (const std::string& m : messages(out)) {
      warned = warned || (m.rfind("12:", 0) == 0 && m.find("warning") != std::string::npos &&
                          m.find("above " + std::string(name) + "'s ") != std::string::npos);
    }
    EXPECT_TRUE(warned) << name << " at " << fastest[id] << "/s\n"
                        << ::testing::PrintToString(messages(out));
  }
}

// A curve of another track that goes on past the line's end cannot share the line's actions:
// the fitter cuts the joints' pieces for it, and the tip's true largest distance, measured here
// by forward kinematics, is what the warning says.
TEST(TipLine, ACurveGoingOnPastTheLineWarnsWithTheTipsTrueDistance) {
  const auto out = compile_text(std::string(kStart) + R"(  - together:
      arm:
        - move: {tip: [200mm, 100mm, 60mm]}
          time: 1s
          path: line
          ease: in-out
      hand:
        - move: {claw: 650}
          time: 1500ms
          ease: in-out
)");
  const auto m = messages(out);
  ASSERT_EQ(m.size(), 1u) << ::testing::PrintToString(m);
  const ServoProgram& p = program_of(out);
  const LineCheck c = check_line(p, 2000, 3000, {200, 100, 60}, quad_in_out);
  std::cout << "line beside a longer curve: worst " << c.worst << " mm at " << c.worst_at
            << " ms\n";
  ASSERT_GT(c.worst, 1.0);
  char mm[16];
  std::snprintf(mm, sizeof mm, "%.2f", c.worst);
  const std::string at =
      std::to_string(c.worst_at / 1000) + "." + std::to_string(c.worst_at % 1000 + 1000).substr(1);
  std::string seconds = at;  // "2.831 s", trailing zeros dropped
  while (seconds.back() == '0') seconds.pop_back();
  if (seconds.back() == '.') seconds.pop_back();
  EXPECT_EQ(m[0], "11:17 warning: the tip strays up to " + std::string(mm) +
                      " mm from this line (at " + seconds +
                      " s), more than its tolerance of 1mm: other tracks' moves during it cut "
                      "the joints' actions where the line cannot choose their targets; keep the "
                      "other tracks straight while it runs, or give it its own stretch of time");
}

TEST(TipLine, ToleranceInMillimetresIsTheTips) {
  const std::string fine = std::string(kStart) + R"(  - move: {tip: [150mm, 80mm, 40mm]}
    time: 800ms
    path: line
    tolerance: 0.5mm
)";
  const std::string loose = std::string(kStart) + R"(  - move: {tip: [150mm, 80mm, 40mm]}
    time: 800ms
    path: line
    tolerance: 3mm
)";
  const auto f = compile_text(fine);
  const auto l = compile_text(loose);
  ASSERT_TRUE(messages(f).empty()) << ::testing::PrintToString(messages(f));
  ASSERT_TRUE(messages(l).empty()) << ::testing::PrintToString(messages(l));
  auto linear = [](double t) { return t; };
  const LineCheck cf = check_line(program_of(f), 2000, 2800, {150, 80, 40}, linear);
  const LineCheck cl = check_line(program_of(l), 2000, 2800, {150, 80, 40}, linear);
  std::cout << "line 0.5 mm: worst " << cf.worst << " mm, " << cf.actions
            << " actions; 3 mm: " << cl.worst << " mm, " << cl.actions << " actions\n";
  EXPECT_LE(cf.worst, 0.5 + 1e-9);
  EXPECT_LE(cl.worst, 3.0 + 1e-9);
  EXPECT_LT(cl.actions, cf.actions);
}

TEST(TipLine, RoundingThatCannotMeetTheToleranceSaysByHowMuch) {
  const auto out = compile_text(std::string(kStart) + R"(  - move: {tip: [200mm, 100mm, 60mm]}
    time: 1s
    path: line
    tolerance: 0.01mm
)");
  const auto m = messages(out);
  ASSERT_EQ(m.size(), 1u) << ::testing::PrintToString(m);
  // Half a unit is 0.12 degrees; at 0.01 mm the whole-unit joints cannot meet the line's end.
  EXPECT_NE(m[0].find("9:11 error: rounding the joints to whole units puts the tip at least "),
            std::string::npos)
      << m[0];
  EXPECT_NE(m[0].find("from the line's end, [200mm, 100mm, 60mm], more than the tolerance of "
                      "0.01mm; give a larger one, e.g. 'tolerance: "),
            std::string::npos)
      << m[0];
}

TEST(TipLine, BelowTheTableAlongTheLineSaysWhere) {
  // back-in, (c + 1)t^3 - ct^2 with c = 1.70158, first runs backwards: it is lowest at
  // t = 2c / (3(c + 1)) = 0.42, where it is -0.100. Up from z = 10 to z = 120 (110 mm) it dips
  // 11 mm below the start, to z = -1: 10% of the line's length before its start, said so in
  // words (a negative percentage of the line would read as nonsense).
  const auto out = compile_text(std::string(kStart) + R"(  - move: {tip: [200mm, 0mm, 10mm]}
    time: 1s
  - move: {tip: [200mm, 0mm, 120mm]}
    time: 1s
    path: line
    ease: back-in
)");
  const auto m = messages(out);
  ASSERT_EQ(m.size(), 1u) << ::testing::PrintToString(m);
  EXPECT_NE(m[0].find("11:11 error: this line goes 1.0 mm below the table where the ease runs "
                      "10% of the line's length before its start, [200mm, 0mm, -1mm]"),
            std::string::npos)
      << m[0];
}

TEST(TipLine, PastTheLinesEndIsSaidInWords) {
  // back-out, the mirror of back-in, runs past its end by the same 0.100 (at t = 0.58). Down
  // from z = 120 to z = 10 (110 mm) it goes 11 mm past the end, to z = -1: 10% of the line's
  // length past its end.
  const auto out = compile_text(std::string(kStart) + R"(  - move: {tip: [200mm, 0mm, 10mm]}
    time: 1s
    path: line
    ease: back-out
)");
  const auto m = messages(out);
  ASSERT_EQ(m.size(), 1u) << ::testing::PrintToString(m);
  EXPECT_NE(m[0].find("9:11 error: this line goes 1.0 mm below the table where the ease runs "
                      "10% of the line's length past its end, [200mm, 0mm, -1mm]"),
            std::string::npos)
      << m[0];
}

TEST(TipLine, JointLimitAlongTheLineSaysWhichJointAndWhere) {
  // From [-50, 150, 100] to [-50, -150, 100] (relative moves: an absolute list point has no
  // negative coordinate) the line passes behind the base: at its middle, [-50, 0, 100], the base
  // must face 180 degrees, 500 + 180 / 0.24 = 1250, 250 above its max 1000. Both ends are at
  // atan2(150, -50) = +-108.4 degrees, 500 +- 451.7: within 0..1000.
  const auto out = compile_text(std::string(kStart) + R"(  - move: {tip: [-250mm, +150mm, -20mm]}
    time: 1s
  - move: {tip: [+0mm, -300mm, 0mm]}
    time: 1s
    path: line
)");
  const auto m = messages(out);
  ASSERT_EQ(m.size(), 1u) << ::testing::PrintToString(m);
  // The line starts where the whole-unit joints put the tip, within about 2 mm of [-50, 150,
  // 100] (half a unit per joint), so its middle, and the base there, are a few units off.
  const std::string head = "11:11 error: this line needs 'base' at ";
  ASSERT_EQ(m[0].rfind(head, 0), 0u) << m[0];
  const int units = std::stoi(m[0].substr(head.size()));
  EXPECT_NEAR(units, 1250, 3) << m[0];
  EXPECT_NE(m[0].find("deg) at 50% of the line, [-50mm, 0mm, "), std::string::npos) << m[0];
  EXPECT_NE(m[0].find(", " + std::to_string(units - 1000) + " above its max 1000"),
            std::string::npos)
      << m[0];
}

// Each servo's pieces (from its previous target to the action's over the action's time), for
// sampling a long program at every millisecond without walking every action each time.
class PieceSampler {
 public:
  explicit PieceSampler(const ServoProgram& p) {
    std::map<int, double> target;
    for (const Keyframe& k : p.keyframes) {
      for (const auto& s : k.targets) {
        const double from = target.count(s.id) ? target[s.id] : s.position;
        pieces_[s.id].push_back({static_cast<double>(k.start_ms),
                                 static_cast<double>(k.start_ms + k.time_ms), from,
                                 static_cast<double>(s.position)});
        target[s.id] = s.position;
      }
    }
  }
  double at(int id, double t) const {
    const std::vector<Piece>& v = pieces_.at(id);
    const auto it =
        std::lower_bound(v.begin(), v.end(), t, [](const Piece& x, double u) { return x.end < u; });
    if (it == v.end()) return v.back().to;
    if (t <= it->start) return it == v.begin() ? it->from : (it - 1)->to;
    return it->from + (it->to - it->from) * (t - it->start) / (it->end - it->start);
  }
  // forward() above, on the four joints without a map (this runs for millions of instants).
  Vec tip(double t) const {
    const double rad = kDegPerUnit * std::numbers::pi / 180;
    const double base = (at(6, t) - 500) * rad;
    const double s = -(at(5, t) - 500) * rad;
    const double e = -(at(4, t) - 500) * rad;
    const double w = -(at(3, t) - 500) * rad;
    const double r = 97 * std::sin(s) + 96 * std::sin(s + e) + 150 * std::sin(s + e + w);
    const double z = 72 + 97 * std::cos(s) + 96 * std::cos(s + e) + 150 * std::cos(s + e + w);
    return {r * std::cos(base), r * std::sin(base), z};
  }

 private:
  struct Piece {
    double start, end, from, to;
  };
  std::map<int, std::vector<Piece>> pieces_;
};

// A line of minutes or hours is searched on a bounded grid and its long actions checked at a
// bounded number of instants (with a margin): the tip must still stay within the millimetre at
// every millisecond (of the 100-minute line, every fifth, to keep the test quick), and the
// line's actions be as long as the controller allows, near enough.
TEST(TipLine, LongLinesAreFollowedWithinTheMillimetreEveryMillisecond) {
  struct Case {
    std::uint32_t ms;
    const char* ease;
    Vec to;
    std::uint32_t every;
  };
  for (const Case& c :
       {Case{700'000, "in-out", {200, 100, 60}, 1}, Case{6'002'000, "linear", {200, 0, 40}, 5}}) {
    const std::string text =
        std::string(kStart) + "  - move: {tip: [" + std::to_string(static_cast<int>(c.to[0])) +
        "mm, " + std::to_string(static_cast<int>(c.to[1])) + "mm, " +
        std::to_string(static_cast<int>(c.to[2])) + "mm]}\n    time: " + std::to_string(c.ms) +
        "ms\n    path: line\n    ease: " + c.ease + "\n";
    const auto out = compile_text(text);
    ASSERT_TRUE(messages(out).empty()) << c.ms << ": " << ::testing::PrintToString(messages(out));
    const ServoProgram& p = program_of(out);
    const PieceSampler s(p);
    const Vec from = s.tip(2000);
    double worst = 0;
    std::uint32_t worst_at = 0;
    for (std::uint32_t t = 2000; t <= 2000 + c.ms; t += c.every) {
      const double u = static_cast<double>(t - 2000) / c.ms;
      const double f = std::string(c.ease) == "linear" ? u : quad_in_out(u);
      const Vec want = {from[0] + (c.to[0] - from[0]) * f, from[1] + (c.to[1] - from[1]) * f,
                        from[2] + (c.to[2] - from[2]) * f};
      const double d = distance(s.tip(t), want);
      if (d > worst) worst = d, worst_at = t;
    }
    EXPECT_LE(worst, 1.0 + 1e-9) << c.ms << " ms line, at " << worst_at;
    const std::size_t fewest = (c.ms + 29'999) / 30'000;
    EXPECT_GE(p.keyframes.size(), 2 + fewest) << c.ms;
    EXPECT_LE(p.keyframes.size(), 2 + fewest + fewest / 4 + 4) << c.ms;
  }
}

TEST(TipLine, PathNeedsATipAndMillimetreTolerance) {
  const auto a = compile_text(std::string(kStart) + R"(  - move: {claw: 400}
    time: 1s
    path: line
)");
  ASSERT_EQ(messages(a).size(), 1u);
  EXPECT_NE(messages(a)[0].find("9:11 error: 'path' is the claw tip's and needs a 'tip'"),
            std::string::npos);
  const auto b = compile_text(std::string(kStart) + R"(  - move: {tip: [200mm, 50mm, 100mm]}
    time: 1s
    path: line
    tolerance: 2
)");
  ASSERT_EQ(messages(b).size(), 1u);
  EXPECT_NE(messages(b)[0].find("10:16 error: a line's 'tolerance' is the tip's distance"),
            std::string::npos)
      << messages(b)[0];
}

}  // namespace
}  // namespace seqc::compiler
