// yaml-cpp's events in the fast reader's terms, for comparing the two readers (the fast-reader
// differential test and the yaml-test-suite check, scripts/yaml-suite.sh).
#pragma once

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/exceptions.h>
#include <yaml-cpp/mark.h>
#include <yaml-cpp/parser.h>

#include <sstream>
#include <string>
#include <vector>

#include "compiler/yaml/yaml_fast.hpp"

namespace seqc::compiler::yaml_detail {

struct Ev {
  FastEvent::Kind kind;
  int pos = 0, line = 0, column = 0;
  std::string value;
  bool operator==(const Ev&) const = default;
};

inline std::string describe(const std::vector<Ev>& events) {
  static const char* const kNames[] = {"Null",   "Scalar",   "SeqStart",
                                       "SeqEnd", "MapStart", "MapEnd"};
  std::string out;
  for (const Ev& e : events) {
    out += kNames[static_cast<int>(e.kind)];
    out +=
        "@" + std::to_string(e.pos) + ":" + std::to_string(e.line) + ":" + std::to_string(e.column);
    if (e.kind == FastEvent::Kind::Scalar) out += "'" + e.value + "'";
    out += " ";
  }
  return out;
}

struct SecondDocument {};

// What yaml-cpp reports, in the fast reader's terms; tags other than "?" are kept in the value
// so they can never compare equal to a fast event.
class Recorder final : public YAML::EventHandler {
 public:
  std::vector<Ev> events;
  void OnDocumentStart(const YAML::Mark&) override {
    if (documents_++ > 0) throw SecondDocument{};
  }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& m, YAML::anchor_t) override { add(FastEvent::Kind::Null, m, ""); }
  void OnAlias(const YAML::Mark& m, YAML::anchor_t) override { add(FastEvent::Kind::Null, m, "*"); }
  void OnAnchor(const YAML::Mark& m, const std::string&) override {
    add(FastEvent::Kind::Null, m, "&");
  }
  void OnScalar(const YAML::Mark& m, const std::string& tag, YAML::anchor_t,
                const std::string& value) override {
    add(FastEvent::Kind::Scalar, m, tag == "?" ? value : "tag " + tag + " " + value);
  }
  void OnSequenceStart(const YAML::Mark& m, const std::string& tag, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {
    add(FastEvent::Kind::SeqStart, m, tag == "?" ? "" : tag);
  }
  void OnSequenceEnd() override { events.push_back({FastEvent::Kind::SeqEnd, 0, 0, 0, ""}); }
  void OnMapStart(const YAML::Mark& m, const std::string& tag, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {
    add(FastEvent::Kind::MapStart, m, tag == "?" ? "" : tag);
  }
  void OnMapEnd() override { events.push_back({FastEvent::Kind::MapEnd, 0, 0, 0, ""}); }

 private:
  void add(FastEvent::Kind kind, const YAML::Mark& m, std::string value) {
    events.push_back({kind, m.pos, m.line, m.column, std::move(value)});
  }
  int documents_ = 0;
};

inline std::vector<Ev> from_fast(const std::vector<FastEvent>& events) {
  std::vector<Ev> out;
  for (const FastEvent& e : events) {
    const bool end = e.kind == FastEvent::Kind::SeqEnd || e.kind == FastEvent::Kind::MapEnd;
    out.push_back({e.kind, end ? 0 : static_cast<int>(e.pos), end ? 0 : static_cast<int>(e.line),
                   end ? 0 : static_cast<int>(e.column), std::string(e.value)});
  }
  return out;
}

// What yaml-cpp reports for the one document of `text`: its events, or why it gave none
// (its error, or a second document, which the loader refuses).
struct YamlCppEvents {
  std::vector<Ev> events;
  std::string error;  // "" when yaml-cpp read the text
};

inline YamlCppEvents yaml_cpp_events(const std::string& text) {
  Recorder recorder;
  YamlCppEvents out;
  try {
    std::istringstream in(text);
    YAML::Parser parser(in);
    for (int i = 0; i < 2 && parser.HandleNextDocument(recorder); ++i) {
    }
  } catch (const YAML::Exception& e) {
    out.error = "yaml-cpp error: " + e.msg;
  } catch (const SecondDocument&) {
    out.error = "yaml-cpp saw a second document";
  }
  out.events = std::move(recorder.events);
  return out;
}

}  // namespace seqc::compiler::yaml_detail
