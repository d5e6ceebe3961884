// The preview page as text (formats/preview_html.hpp): self-contained (no URL, no external
// source, no link), with the compiled actions and the arm's geometry embedded for its script in
// the form the script reads, and nothing in the data able to close its <script> element. How
// the page looks and what it shows at an instant is checked in Chromium
// (preview_chromium_test.py).
#include <gtest/gtest.h>

#include <string>

#include "compiler/formats/preview_html.hpp"
#include "tests/compiler/lang_test_util.hpp"

namespace seqc::compiler {
namespace {

using compiler::testing::compile_text;
using compiler::testing::program_of;

const char* const kArm = R"(robot: xarm
tempo: 120
meter: 4/4
sequence:
  - move: {claw: 700}
    time: 200ms
  - move: {claw: 300, base: 600}
    time: 400ms
  - wait: 1400ms
)";

std::string page_of(const std::string& text, const std::string& title = "arm.yaml") {
  const auto out = compile_text(text);
  const compiler::ServoProgram& p = program_of(out);
  const double end = static_cast<double>(p.duration_ms());
  return preview_page(title, {""}, {preview_servo_part(p, title, end)}, end);
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(PreviewPage, NamesNoUrlAndLoadsNothing) {
  const std::string html = page_of(kArm);
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  for (const char* bad : {"http:", "https:", "src=", "href=", "@import", "url(", "<link", "<iframe",
                          "<img", "fetch(", "XMLHttpRequest"}) {
    EXPECT_EQ(html.find(bad), std::string::npos) << bad;
  }
  EXPECT_EQ(count(html, "<script"), 2u);  // the data and the script, both inline
  EXPECT_EQ(count(html, "id=\"seqc-state\""), 1u);
}

TEST(PreviewPage, EmbedsTheActionsTheGeometryAndTheBars) {
  const std::string html = page_of(kArm);
  // [start, time, [[servo index, target]...]]: claw is index 0 and base index 5 of the xArm's
  // six servos, id order.
  EXPECT_NE(html.find("\"actions\":[[0,200,[[0,700]]],[200,400,[[0,300],[5,600]]],"
                      "[600,1400,[[0,300],[5,600]]]]"),
            std::string::npos)
      << html.substr(html.find("\"actions\""), 200);
  EXPECT_NE(html.find("\"columns\":[\"claw\",\"base\"]"), std::string::npos);
  EXPECT_NE(html.find("\"arm\":{\"base_height\":72,\"upper_arm\":97,\"forearm\":96,\"hand\":150,"
                      "\"degrees_per_unit\":0.240000,\"joints\":{\"base\":{\"servo\":\"base\","
                      "\"zero\":500,\"sign\":1},\"shoulder\":{\"servo\":\"shoulder\",\"zero\":500,"
                      "\"sign\":-1},\"elbow\":{\"servo\":\"elbow\",\"zero\":500,\"sign\":-1},"
                      "\"wrist\":{\"servo\":\"wrist_pitch\",\"zero\":500,\"sign\":-1}},"
                      "\"claw\":\"claw\"}"),
            std::string::npos);
  // 120 bpm in 4/4: a beat every 500 ms, a bar every 2 s; the program lasts 2 s.
  EXPECT_NE(html.find("\"bars\":[0,2000],\"beats\":[0,500,1000,1500,2000]"), std::string::npos);
  // The lanes are the plot's, with a playhead, in HTML's own <svg> (no namespace URL).
  EXPECT_EQ(count(html, "class=\"playhead\""), 1u);
}

TEST(PreviewPage, ATitleCannotCloseTheScript) {
  const std::string html = page_of(kArm, "a</script><b>.yaml");
  EXPECT_EQ(count(html, "</script>"), 2u);
  EXPECT_NE(html.find("a\\u003c/script\\u003e\\u003cb\\u003e.yaml"), std::string::npos);
  EXPECT_NE(html.find("<title>a&lt;/script&gt;&lt;b&gt;.yaml</title>"), std::string::npos);
}

// "<!--<script>" in the data would make HTML read the island's end as part of it: the JSON holds
// no <, > or & at all, nor a raw U+2028 or U+2029, each written as its \u escape.
TEST(PreviewPage, TheDataHoldsNoMarkup) {
  const std::string html = page_of(kArm, "</script><!--<script>alert(1)// & \u2028\u2029.yaml");
  EXPECT_EQ(count(html, "<script"), 2u);
  EXPECT_EQ(count(html, "</script>"), 2u);
  EXPECT_EQ(count(html, "<!--"), 0u);
  EXPECT_NE(html.find("\"title\":\"\\u003c/script\\u003e\\u003c!--\\u003cscript\\u003ealert(1)// "
                      "\\u0026 \\u2028\\u2029.yaml\""),
            std::string::npos);
  EXPECT_NE(html.find("<title>&lt;/script&gt;&lt;!--&lt;script&gt;alert(1)// &amp; "
                      "\u2028\u2029.yaml</title>"),
            std::string::npos);
}

// The skeleton's @name@ places are filled once: none is left, and a title that looks like one
// is copied as written, not filled again.
TEST(PreviewPage, FillsTheSkeletonOnce) {
  const std::string html = page_of(kArm, "@script@.yaml");
  for (const char* place : {"@title@", "@style@", "@end@", "@audio@", "@lanes@", "@data@"}) {
    EXPECT_EQ(html.find(place), std::string::npos) << place;
  }
  EXPECT_NE(html.find("<title>@script@.yaml</title>"), std::string::npos);
  EXPECT_NE(html.find("<span id=\"title\">@script@.yaml</span>"), std::string::npos);
  EXPECT_EQ(count(html, "\"use strict\";"), 1u);
}

TEST(PreviewPage, AShowNamesItsPerformers) {
  const auto a = compile_text(kArm);
  const auto b = compile_text("robot: lsc-16\nsequence:\n  - move: {ch1: 1600}\n    time: 1s\n");
  const std::string html = preview_page(
      "show", {"arm", "legs"},
      {preview_servo_part(program_of(a), "a", 2000), preview_servo_part(program_of(b), "b", 2000)},
      2000);
  EXPECT_NE(html.find("\"show\":true"), std::string::npos);
  EXPECT_NE(html.find("{\"name\":\"arm\",\"kind\":\"servo\""), std::string::npos);
  EXPECT_NE(html.find("{\"name\":\"legs\",\"kind\":\"servo\""), std::string::npos);
  EXPECT_NE(html.find("\"arm\":null"), std::string::npos);  // the LSC-16 has no geometry
  EXPECT_EQ(count(html, "class=\"playhead\""), 2u);
}

}  // namespace
}  // namespace seqc::compiler
