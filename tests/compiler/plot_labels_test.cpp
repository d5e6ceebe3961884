// The markers' labels of `seqc plot` (and of the preview, which shows the same picture) never
// overlap: the SVG is read back here and every label's box is estimated as characters x font size
// x 0.6 wide and one font size high, above its baseline.
#include <gtest/gtest.h>

#include <cstddef>
#include <string>
#include <vector>

#include "compiler/formats/plot_svg.hpp"
#include "tests/compiler/lang_test_util.hpp"

namespace seqc::compiler {
namespace {

using testing::compile_text;
using testing::program_of;

struct Label {
  double x = 0, y = 0, size = 11;
  std::string text;
  bool marker = false;  // inside a <g class="marker">, or the count of hidden labels
};

std::string attribute(const std::string& tag, const std::string& name) {
  const std::string key = " " + name + "=\"";
  const auto at = tag.find(key);
  if (at == std::string::npos) return "";
  const auto start = at + key.size();
  return tag.substr(start, tag.find('"', start) - start);
}

std::size_t characters(const std::string& escaped) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < escaped.size(); ++i) {
    if (escaped[i] == '&') i = escaped.find(';', i);  // one character per entity
    if ((static_cast<unsigned char>(escaped[i]) & 0xC0) != 0x80) ++n;
  }
  return n;
}

// Every <text> of the picture, in order.
std::vector<Label> labels(const std::string& svg) {
  std::vector<Label> out;
  bool in_marker = false;
  for (std::size_t at = 0; at < svg.size();) {
    const auto open = svg.find('<', at);
    if (open == std::string::npos) break;
    const auto close = svg.find('>', open);
    const std::string tag = svg.substr(open, close - open + 1);
    if (tag.rfind("<g class=\"marker\"", 0) == 0) in_marker = true;
    if (tag == "</g>") in_marker = false;
    if (tag.rfind("<text ", 0) == 0) {
      Label l;
      l.x = std::stod(attribute(tag, "x"));
      l.y = std::stod(attribute(tag, "y"));
      if (const std::string size = attribute(tag, "font-size"); !size.empty())
        l.size = std::stod(size);
      const auto end = svg.find("</text>", close);
      l.text = svg.substr(close + 1, end - close - 1);
      l.marker = in_marker || attribute(tag, "class") == "hidden-labels";
      out.push_back(l);
    }
    at = close + 1;
  }
  return out;
}

// The first pair of marker labels whose boxes overlap, as "a / b", or "".
std::string overlapping(const std::vector<Label>& all) {
  std::vector<Label> marks;
  for (const Label& l : all) {
    if (l.marker) marks.push_back(l);
  }
  for (std::size_t i = 0; i < marks.size(); ++i) {
    for (std::size_t j = i + 1; j < marks.size(); ++j) {
      const Label& a = marks[i];
      const Label& b = marks[j];
      const double a_right = a.x + static_cast<double>(characters(a.text)) * a.size * 0.6;
      const double b_right = b.x + static_cast<double>(characters(b.text)) * b.size * 0.6;
      const bool across = a.x < b_right && b.x < a_right;
      const bool down = a.y - a.size < b.y && b.y - b.size < a.y;
      if (across && down) return a.text + " / " + b.text;
    }
  }
  return "";
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(PlotLabels, ATempoChangeAndACueAtOneInstantTakeTheTwoRows) {
  // Two seconds of moves, then "tempo 90" and "at 4b" both at 2 s (x = 150 + 2000/2667 x 926
  // = 844.4...): the cue is the second marker, so it takes the lower row (y 74 - 12 = 62)
  // whatever comes first, and the tempo label the upper one (y 52).
  auto out = compile_text(R"(robot: xarm
tempo: 120
sequence:
  - move: home
    time: 1s
  - move: {base: 600}
    time: 1s
  - tempo: 90
  - move: {base: 500}
    at: 4b
    time: 1b
)");
  const std::string svg = plot_servo_program(program_of(out), {"t.yaml", nullptr, {}, {}});
  const std::vector<Label> all = labels(svg);
  EXPECT_EQ(overlapping(all), "");
  std::vector<std::string> drawn;
  for (const Label& l : all) {
    if (l.marker) drawn.push_back(l.text + " @" + std::to_string(static_cast<int>(l.y)));
  }
  EXPECT_EQ(drawn, (std::vector<std::string>{"tempo 90 @52", "at 4b @62"}));
}

TEST(PlotLabels, ALongPieceWithASectionEveryTwoBarsHidesWhatDoesNotFit) {
  // 82 bars of 2 s at 120 bpm in 4/4, a section every 2 bars: 41 labels "section verse" of
  // 13 x 10 x 0.6 = 78 px each, 4 s = 22.4 px apart on the 926 px of the lanes; two rows hold
  // one label per 80 px each, so most are hidden, and every marker keeps its <title>.
  std::string text =
      "robot: xarm\ntempo: 120\nmeter: 4/4\nsections:\n  verse:\n"
      "    - move: {base: 510}\n      time: 1bar\n"
      "    - move: {base: 490}\n      time: 1bar\n"
      "sequence:\n";
  for (int i = 0; i < 41; ++i) text += "  - section: verse\n";
  auto out = compile_text(text);
  const std::string svg = plot_servo_program(program_of(out), {"long.yaml", nullptr, {}, {}});
  const std::vector<Label> all = labels(svg);
  EXPECT_EQ(overlapping(all), "");
  EXPECT_EQ(count(svg, "<title>section verse</title>"), 41u);
  std::size_t drawn = 0;
  std::string note;
  for (const Label& l : all) {
    if (l.text == "section verse") ++drawn;
    if (l.text.find("hidden") != std::string::npos) note = l.text;
  }
  // Left edges 22.4 px apart: a row takes every fourth label (89.6 px >= 78 + 2), the two rows
  // taking turns, so labels 0, 1, 4, 5, 8, 9, ... 40: 21 drawn, 20 hidden.
  EXPECT_EQ(drawn, 21u);
  EXPECT_EQ(note, "20 labels hidden");
}

}  // namespace
}  // namespace seqc::compiler
