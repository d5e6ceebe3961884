// What the language features (features.hpp) share: a request read once (its document, the
// position asked about, the analysis of the file), the answer of each feature, and the
// protocol's shapes for ranges and locations. Internal to runtime/lsp.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "compiler/timeline/exact_time.hpp"
#include "compiler/timeline/tempo_map.hpp"
#include "runtime/lsp/analysis.hpp"
#include "runtime/lsp/features.hpp"

namespace seqc::lsp {

struct Request {
  FeatureContext& ctx;
  const nlohmann::json& params;
  std::string uri;   // params.textDocument.uri
  std::string path;  // its path
  std::unique_ptr<Analysis> analysis;
  std::optional<std::uint32_t> file;  // the document's index in the analysis
  std::optional<TextPos> position;    // params.position, when given
};

// The request's document read and analysed (its steps timed with `walk`: only the features
// that show times need the walk); `file` unset when it cannot be read.
Request read_request(const nlohmann::json& params, FeatureContext& ctx, bool walk);

// A line or column number of the protocol (a non-negative integer below 2^32), nullopt otherwise.
std::optional<std::uint32_t> protocol_number(const nlohmann::json& v);
// A Position object, nullopt when it is none.
std::optional<TextPos> protocol_position(const nlohmann::json& v);

nlohmann::json position_json(TextPos p);
nlohmann::json range_json(const Analysis& a, const Span& s);
// A Location (uri and range) of `s`, in the file it lies in.
nlohmann::json location_json(const Request& r, const Span& s);
std::string uri_of(const Request& r, std::uint32_t file);

// "12.500 s": an instant of the sequence to the millisecond.
std::string seconds_text(compiler::ExactMs t);
// "5:3" (bar 5, beat 3; "5:2.5" between beats) where a tempo and a meter count `t`,
// "beat 9" where only a tempo does, "" where no tempo is set.
std::string bar_beat_text(const compiler::TempoMap& map, compiler::ExactMs t);
// "12.500 s · 5:3", or "12.500 s" without a bar and beat.
std::string instant_text(const compiler::TempoMap& map, compiler::ExactMs t);
// "500 ms" under a second, "1.500 s" from one on.
std::string duration_text(compiler::ExactMs d);

// The inlay hint of a step walked at `t`: "2.500 s · 2:2 · 500 ms", a block's "start – end".
std::string step_hint_text(const Analysis& a, const compiler::YamlNode& step,
                           const compiler::StepTime& t);
// The first performance of the section called `name`, nullptr when none was walked.
const compiler::StepTime* section_performance(const Analysis& a, const std::string& name);

nlohmann::json inlay_hints(Request& r);
nlohmann::json hover(Request& r);
nlohmann::json definition(Request& r);
nlohmann::json references(Request& r);
nlohmann::json prepare_rename(Request& r);
nlohmann::json rename(Request& r);
nlohmann::json completion(Request& r);
nlohmann::json code_actions(Request& r);
nlohmann::json document_symbols(Request& r);

}  // namespace seqc::lsp
