// The language features (runtime/lsp/features.hpp) answering requests about hand-written files
// read through an in-memory FileReader: inlay hints with musical time, hover, definition,
// references, rename, completion, code actions, the outline, and empty answers for files that
// are no choreography, half-typed ones and positions past the end.
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "runtime/lsp/features.hpp"

namespace seqc::lsp {
namespace {

using nlohmann::json;

class MemoryFiles : public FileReader {
 public:
  std::map<std::string, std::string> files;
  Result<std::string> read(const std::string& path) override {
    auto it = files.find(path);
    if (it == files.end()) return make_error(path + ": no such file");
    return it->second;
  }
};

std::string to_path(std::string_view uri) {
  return uri.rfind("file://", 0) == 0 ? std::string(uri.substr(7)) : std::string();
}
std::string to_uri(std::string_view path) { return "file://" + std::string(path); }

// 120 bpm in 4/4: a beat is 500 ms, a bar 2 s.
constexpr const char* kDance = R"(robot: xarm
tempo: 120
meter: 4/4
poses:
  ready: {claw: 300, elbow: 650}
sections:
  nod:
    params: {amount: 40}
    steps:
      - move: {wrist_pitch: +$amount}
        time: 1b
      - move: {wrist_pitch: -$amount}
        time: 1b
sequence:
  - move: home
    time: 2s
  - move: ready
    time: 500ms
    ease: in-out
  - move: {base: 600}
    time: 1b
  - section: nod
    with: {amount: 80}
)";

class LspFeatures : public ::testing::Test {
 protected:
  MemoryFiles files;
  FeatureContext ctx{files, to_path, to_uri};

  json ask(std::string_view method, json params) {
    std::optional<json> answer = answer_feature(method, params, ctx);
    EXPECT_TRUE(answer.has_value()) << method;
    return answer.value_or(json());
  }
  static json at(const char* uri, int line, int character) {
    return {{"textDocument", {{"uri", uri}}},
            {"position", {{"line", line}, {"character", character}}}};
  }
  static json range(int l0, int c0, int l1, int c1) {
    return {{"start", {{"line", l0}, {"character", c0}}},
            {"end", {{"line", l1}, {"character", c1}}}};
  }
  std::string hover_text(const char* uri, int line, int character) {
    const json h = ask("textDocument/hover", at(uri, line, character));
    return h.is_object() ? h["contents"]["value"].get<std::string>() : std::string();
  }
  static bool has_label(const json& items, const std::string& label) {
    for (const json& item : items) {
      if (item["label"] == label) return true;
    }
    return false;
  }
};

TEST_F(LspFeatures, InlayHintsGiveStartBarBeatAndDuration) {
  files.files["/d/dance.yaml"] = kDance;
  const json hints =
      ask("textDocument/inlayHint",
          {{"textDocument", {{"uri", "file:///d/dance.yaml"}}}, {"range", range(0, 0, 40, 0)}});
  std::map<int, std::string> by_line;
  for (const json& h : hints) by_line[h["position"]["line"].get<int>()] = h["label"];
  EXPECT_EQ(by_line[14], "0.000 s \u00B7 1:1 \u00B7 2.000 s");
  EXPECT_EQ(by_line[16], "2.000 s \u00B7 2:1 \u00B7 500 ms");
  // The third step starts at 2.5 s: beat 5 of the song, bar 2 beat 2.
  EXPECT_EQ(by_line[19], "2.500 s \u00B7 2:2 \u00B7 500 ms");
  // A section's performance: its span; the section's own steps at their first performance.
  EXPECT_EQ(by_line[21], "3.000 s \u00B7 2:3 \u2013 4.000 s \u00B7 3:1");
  EXPECT_EQ(by_line[9], "3.000 s \u00B7 2:3 \u00B7 500 ms");
  EXPECT_EQ(by_line[11], "3.500 s \u00B7 2:4 \u00B7 500 ms");
  // At the end of the step's first line ("  - move: {base: 600}").
  for (const json& h : hints) {
    if (h["position"]["line"] == 19) {
      EXPECT_EQ(h["position"]["character"], 21);
    }
  }
}

TEST_F(LspFeatures, InlayHintsOnlyInsideTheRequestedRange) {
  files.files["/d/dance.yaml"] = kDance;
  const json hints =
      ask("textDocument/inlayHint",
          {{"textDocument", {{"uri", "file:///d/dance.yaml"}}}, {"range", range(17, 0, 20, 0)}});
  ASSERT_EQ(hints.size(), 1u);
  EXPECT_EQ(hints[0]["position"]["line"], 19);
}

TEST_F(LspFeatures, InlayHintsCountBeatsWithoutAMeter) {
  files.files["/d/beats.yaml"] =
      "robot: xarm\ntempo: 60\nsequence:\n  - move: home\n    time: 3b\n  - wait: 1s\n";
  const json hints =
      ask("textDocument/inlayHint", {{"textDocument", {{"uri", "file:///d/beats.yaml"}}}});
  ASSERT_EQ(hints.size(), 2u);
  EXPECT_EQ(hints[1]["label"], "3.000 s \u00B7 beat 4 \u00B7 1.000 s");
}

TEST_F(LspFeatures, InlayHintsStartAfterAnAtAndCountRepeats) {
  files.files["/d/cue.yaml"] =
      "robot: xarm\ntempo: 120\nmeter: 4/4\nsequence:\n  - move: home\n    time: 1s\n"
      "  - move: {base: 600}\n    at: 2bar\n    time: 1b\n"
      "  - repeat: 3\n    do:\n      - move: {base: +10}\n        time: 1b\n";
  const json hints =
      ask("textDocument/inlayHint", {{"textDocument", {{"uri", "file:///d/cue.yaml"}}}});
  std::map<int, std::string> by_line;
  for (const json& h : hints) by_line[h["position"]["line"].get<int>()] = h["label"];
  // `at: 2bar` starts it on bar 3, after the rest from 1 s.
  EXPECT_EQ(by_line[6], "4.000 s \u00B7 3:1 \u00B7 500 ms");
  EXPECT_EQ(by_line[9], "4.500 s \u00B7 3:2 \u2013 6.000 s \u00B7 4:1");
  EXPECT_EQ(by_line[11], "4.500 s \u00B7 3:2 \u00B7 500 ms \u00B7 \u00D73");
}

TEST_F(LspFeatures, InlayHintsForTheCar) {
  files.files["/d/car.yaml"] =
      "robot: raspblock\ntempo: 120\nmeter: 4/4\nsequence:\n  - move: home\n    time: 1bar\n"
      "  - move: {pan: 2000}\n    time: 2b\n";
  const json hints =
      ask("textDocument/inlayHint", {{"textDocument", {{"uri", "file:///d/car.yaml"}}}});
  ASSERT_EQ(hints.size(), 2u);
  EXPECT_EQ(hints[1]["label"], "2.000 s \u00B7 2:1 \u00B7 1.000 s");
}

TEST_F(LspFeatures, HoverSaysWhatANameStandsFor) {
  files.files["/d/dance.yaml"] = kDance;
  const char* uri = "file:///d/dance.yaml";
  EXPECT_NE(hover_text(uri, 16, 11).find("{claw: 300, elbow: 650}"), std::string::npos);
  const std::string section = hover_text(uri, 21, 14);
  EXPECT_NE(section.find("amount: 40"), std::string::npos) << section;
  EXPECT_NE(section.find("length 1.000 s (2 beats)"), std::string::npos) << section;
  const std::string servo = hover_text(uri, 19, 13);
  EXPECT_NE(servo.find("range 0\u20131000 units"), std::string::npos) << servo;
  EXPECT_NE(servo.find("(375\u00B0/s)"), std::string::npos) << servo;
  EXPECT_NE(hover_text(uri, 18, 11).find("starts and ends slowly"), std::string::npos);
  const std::string step = hover_text(uri, 19, 5);
  EXPECT_NE(step.find("starts 2.500 s \u00B7 2:2, ends 3.000 s \u00B7 2:3"), std::string::npos)
      << step;
  EXPECT_NE(step.find("tempo 120 bpm, meter 4/4"), std::string::npos) << step;
  EXPECT_NE(hover_text(uri, 9, 30).find("default `40`"), std::string::npos);
  EXPECT_TRUE(ask("textDocument/hover", at(uri, 1, 1)).is_null());  // `tempo` names nothing
}

TEST_F(LspFeatures, UnderASongHintsCountItsBarsAndHoverSaysWhereInTheAudio) {
  files.files["/d/song.yaml"] =
      "robot: xarm\nmusic:\n  file: song.ogg\n  downbeat: 0.750s\n  tempo: 60\n  meter: 3/4\n"
      "sequence:\n  - move: home\n    time: 4b\n  - wait: 1b\n";
  const json hints =
      ask("textDocument/inlayHint", {{"textDocument", {{"uri", "file:///d/song.yaml"}}}});
  ASSERT_EQ(hints.size(), 2u);
  EXPECT_EQ(hints[1]["label"], "4.000 s \u00B7 2:2 \u00B7 1.000 s");
  const std::string step = hover_text("file:///d/song.yaml", 9, 5);
  EXPECT_NE(step.find("4.750 s into the song"), std::string::npos) << step;
  EXPECT_NE(step.find("tempo 60 bpm, meter 3/4"), std::string::npos) << step;
}

TEST_F(LspFeatures, DefinitionOfPoseSectionParameterAndInclude) {
  files.files["/d/dance.yaml"] = kDance;
  const char* uri = "file:///d/dance.yaml";
  json def = ask("textDocument/definition", at(uri, 16, 12));
  EXPECT_EQ(def["uri"], uri);
  EXPECT_EQ(def["range"], range(4, 2, 4, 7));
  EXPECT_EQ(ask("textDocument/definition", at(uri, 21, 13))["range"], range(6, 2, 6, 5));
  // `$amount` in the section's steps and `amount` in `with:` go to the parameter's key.
  EXPECT_EQ(ask("textDocument/definition", at(uri, 9, 30))["range"], range(7, 13, 7, 19));
  EXPECT_EQ(ask("textDocument/definition", at(uri, 22, 12))["range"], range(7, 13, 7, 19));

  files.files["/d/main.yaml"] = "robot: xarm\nsequence:\n  - include: moves/bridge.yaml\n";
  files.files["/d/moves/bridge.yaml"] = "sequence:\n  - move: home\n    time: 1s\n";
  def = ask("textDocument/definition", at("file:///d/main.yaml", 2, 16));
  EXPECT_EQ(def["uri"], "file:///d/moves/bridge.yaml");
  EXPECT_EQ(def["range"], range(0, 0, 0, 0));
}

TEST_F(LspFeatures, ReferencesWithAndWithoutTheDeclaration) {
  files.files["/d/dance.yaml"] = kDance;
  json params = at("file:///d/dance.yaml", 4, 3);
  EXPECT_EQ(ask("textDocument/references", params).size(), 2u);
  params["context"] = {{"includeDeclaration", false}};
  const json refs = ask("textDocument/references", params);
  ASSERT_EQ(refs.size(), 1u);
  EXPECT_EQ(refs[0]["range"], range(16, 10, 16, 15));
}

TEST_F(LspFeatures, RenameAPoseAcrossIncludedFiles) {
  files.files["/d/main.yaml"] =
      "robot: xarm\nposes:\n  ready: {claw: 300}\nsequence:\n  - move: ready\n    time: 1s\n"
      "  - include: more.yaml\n";
  files.files["/d/more.yaml"] = "sequence:\n  - move: ready\n    time: 1s\n";
  json params = at("file:///d/main.yaml", 2, 4);
  const json prepared = ask("textDocument/prepareRename", params);
  EXPECT_EQ(prepared["range"], range(2, 2, 2, 7));
  EXPECT_EQ(prepared["placeholder"], "ready");
  params["newName"] = "set";
  const json edit = ask("textDocument/rename", params);
  const json& main = edit["changes"]["file:///d/main.yaml"];
  ASSERT_EQ(main.size(), 2u);
  EXPECT_EQ(main[0]["range"], range(2, 2, 2, 7));
  EXPECT_EQ(main[0]["newText"], "set");
  EXPECT_EQ(main[1]["range"], range(4, 10, 4, 15));
  const json& more = edit["changes"]["file:///d/more.yaml"];
  ASSERT_EQ(more.size(), 1u);
  EXPECT_EQ(more[0]["range"], range(1, 10, 1, 15));
  // Not a name the language takes.
  params["newName"] = "9 lives";
  EXPECT_TRUE(ask("textDocument/rename", params).is_null());
}

TEST_F(LspFeatures, RenameAParameterEverywhereItIsUsed) {
  files.files["/d/dance.yaml"] = kDance;
  json params = at("file:///d/dance.yaml", 7, 15);
  params["newName"] = "size";
  const json edits = ask("textDocument/rename", params)["changes"]["file:///d/dance.yaml"];
  ASSERT_EQ(edits.size(), 4u);
  EXPECT_EQ(edits[0]["range"], range(7, 13, 7, 19));    // params: {amount: 40}
  EXPECT_EQ(edits[1]["range"], range(9, 30, 9, 36));    // +$amount
  EXPECT_EQ(edits[2]["range"], range(11, 30, 11, 36));  // -$amount
  EXPECT_EQ(edits[3]["range"], range(22, 11, 22, 17));  // with: {amount: 80}
  EXPECT_TRUE(ask("textDocument/prepareRename", at("file:///d/dance.yaml", 15, 5)).is_null());
}

TEST_F(LspFeatures, CompletionOffersKeysAndNames) {
  const std::string base = kDance;
  const char* uri = "file:///d/dance.yaml";
  // A new step at the end of the sequence.
  files.files["/d/dance.yaml"] = base + "  - \n";
  json items = ask("textDocument/completion", at(uri, 23, 4));
  EXPECT_TRUE(has_label(items, "move"));
  EXPECT_TRUE(has_label(items, "section"));
  EXPECT_TRUE(has_label(items, "wait"));
  EXPECT_FALSE(has_label(items, "sequence"));
  // A key of the step, under its verb.
  files.files["/d/dance.yaml"] = base + "  - move: ready\n    \n";
  items = ask("textDocument/completion", at(uri, 24, 4));
  EXPECT_TRUE(has_label(items, "time"));
  EXPECT_TRUE(has_label(items, "ease"));
  // A step of a `together` track.
  files.files["/d/dance.yaml"] = base + "  - together:\n      arm:\n        - \n";
  EXPECT_TRUE(has_label(ask("textDocument/completion", at(uri, 25, 10)), "move"));
  // The keys of `robot:` and of a servo definition.
  files.files["/d/robot.yaml"] =
      "robot:\n  profile: lsc-16\n  \n  servos:\n    arm: {id: 0}\n    leg:\n      \n"
      "sequence:\n  - wait: 1s\n";
  items = ask("textDocument/completion", at("file:///d/robot.yaml", 2, 2));
  EXPECT_TRUE(has_label(items, "mirror"));
  EXPECT_FALSE(has_label(items, "max_speed"));
  items = ask("textDocument/completion", at("file:///d/robot.yaml", 6, 6));
  EXPECT_TRUE(has_label(items, "max_speed"));
  EXPECT_FALSE(has_label(items, "mirror"));
  // A top-level key.
  files.files["/d/dance.yaml"] = base + "\n";
  items = ask("textDocument/completion", at(uri, 23, 0));
  EXPECT_TRUE(has_label(items, "sequence"));
  EXPECT_TRUE(has_label(items, "poses"));
  // Values: poses, sections, easings, units; servos in a flow map, also half-typed.
  files.files["/d/dance.yaml"] = base + "  - move: \n";
  items = ask("textDocument/completion", at(uri, 23, 10));
  EXPECT_TRUE(has_label(items, "ready"));
  EXPECT_TRUE(has_label(items, "home"));
  files.files["/d/dance.yaml"] = base + "  - section: \n";
  EXPECT_TRUE(has_label(ask("textDocument/completion", at(uri, 23, 13)), "nod"));
  files.files["/d/dance.yaml"] = base + "  - move: home\n    ease: \n";
  EXPECT_TRUE(has_label(ask("textDocument/completion", at(uri, 24, 10)), "sine-in-out"));
  files.files["/d/dance.yaml"] = base + "  - wait: 500\n";
  EXPECT_TRUE(has_label(ask("textDocument/completion", at(uri, 23, 14)), "500ms"));
  files.files["/d/dance.yaml"] = base + "  - section: nod\n    with: {am\n";
  items = ask("textDocument/completion", at(uri, 24, 13));
  EXPECT_TRUE(has_label(items, "amount"));
  EXPECT_FALSE(has_label(items, "claw"));
  files.files["/d/dance.yaml"] = base + "  - move: {cl\n";
  items = ask("textDocument/completion", at(uri, 23, 15));
  EXPECT_TRUE(has_label(items, "claw"));
  EXPECT_TRUE(has_label(items, "wrist_pitch"));
}

TEST_F(LspFeatures, CodeActionAppliesDidYouMean) {
  files.files["/d/dance.yaml"] = "robot: xarm\nsequence:\n  - move: home\n    tme: 500ms\n";
  json params = {{"textDocument", {{"uri", "file:///d/dance.yaml"}}},
                 {"range", range(3, 4, 3, 4)},
                 {"context",
                  {{"diagnostics",
                    {{{"range", range(3, 4, 3, 4)},
                      {"severity", 1},
                      {"message", "unknown key 'tme' in a move step; did you mean 'time'?"}}}}}}};
  const json actions = ask("textDocument/codeAction", params);
  ASSERT_EQ(actions.size(), 1u);
  EXPECT_EQ(actions[0]["kind"], "quickfix");
  const json& edit = actions[0]["edit"]["changes"]["file:///d/dance.yaml"][0];
  EXPECT_EQ(edit["range"], range(3, 4, 3, 7));
  EXPECT_EQ(edit["newText"], "time");

  // The word quoted where the diagnostic starts, not the first one the message quotes.
  params["context"]["diagnostics"][0]["range"] = range(22, 11, 22, 11);
  params["context"]["diagnostics"][0]["message"] =
      "section 'nod' has no parameter 'amout'; did you mean 'amount'?";
  files.files["/d/dance.yaml"] =
      std::string(kDance).replace(std::string(kDance).find("{amount: 80}"), 12, "{amout: 80}");
  const json param = ask("textDocument/codeAction", params);
  ASSERT_EQ(param.size(), 1u);
  EXPECT_EQ(param[0]["edit"]["changes"]["file:///d/dance.yaml"][0]["range"], range(22, 11, 22, 16));
  EXPECT_EQ(param[0]["edit"]["changes"]["file:///d/dance.yaml"][0]["newText"], "amount");

  // "write '500ms' or '500s'": one fix each.
  files.files["/d/dance.yaml"] = "robot: xarm\nsequence:\n  - move: home\n    time: 500\n";
  params["context"]["diagnostics"][0]["range"] = range(3, 10, 3, 10);
  params["context"]["diagnostics"][0]["message"] =
      "time '500' has no unit; write '500ms' or '500s'";
  const json units = ask("textDocument/codeAction", params);
  ASSERT_EQ(units.size(), 2u);
  EXPECT_EQ(units[1]["edit"]["changes"]["file:///d/dance.yaml"][0]["newText"], "500s");
  EXPECT_EQ(units[1]["edit"]["changes"]["file:///d/dance.yaml"][0]["range"], range(3, 10, 3, 13));
}

TEST_F(LspFeatures, DocumentSymbolsOutlinePosesAndSections) {
  files.files["/d/dance.yaml"] = kDance;
  const json symbols =
      ask("textDocument/documentSymbol", {{"textDocument", {{"uri", "file:///d/dance.yaml"}}}});
  ASSERT_EQ(symbols.size(), 2u);
  EXPECT_EQ(symbols[0]["name"], "ready");
  EXPECT_EQ(symbols[0]["detail"], "pose");
  EXPECT_EQ(symbols[1]["name"], "nod");
  ASSERT_EQ(symbols[1]["children"].size(), 1u);
  EXPECT_EQ(symbols[1]["children"][0]["name"], "amount");
}

TEST_F(LspFeatures, EmptyAnswersForWhatIsNoChoreography) {
  files.files["/d/notes.txt"] = "just: [some, text";
  files.files["/d/half.yaml"] = "robot: xarm\nsequence:\n  - move: {claw: \n";
  files.files["/d/dance.yaml"] = kDance;
  for (const char* uri : {"file:///d/notes.txt", "file:///d/half.yaml", "file:///d/missing.yaml",
                          "file:///d/dance.yaml"}) {
    const int line = std::string(uri) == "file:///d/dance.yaml" ? 999 : 1;
    json params = at(uri, line, 3);
    EXPECT_TRUE(ask("textDocument/hover", params).is_null()) << uri;
    EXPECT_TRUE(ask("textDocument/definition", params).is_null()) << uri;
    EXPECT_EQ(ask("textDocument/references", params), json::array()) << uri;
    params["newName"] = "x";
    EXPECT_TRUE(ask("textDocument/rename", params).is_null()) << uri;
  }
  EXPECT_EQ(ask("textDocument/inlayHint", {{"textDocument", {{"uri", "file:///d/notes.txt"}}}}),
            json::array());
  EXPECT_EQ(
      ask("textDocument/documentSymbol", {{"textDocument", {{"uri", "file:///d/half.yaml"}}}}),
      json::array());
  EXPECT_EQ(ask("textDocument/completion", at("file:///d/dance.yaml", 999, 0)), json::array());
  EXPECT_EQ(ask("textDocument/hover", json::object()), nullptr);
  EXPECT_EQ(ask("textDocument/inlayHint", "nonsense"), json::array());
  EXPECT_FALSE(answer_feature("textDocument/formatting", json::object(), ctx).has_value());
}

}  // namespace
}  // namespace seqc::lsp
