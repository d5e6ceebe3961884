// No language features beyond diagnostics: the server advertises none and answers every other
// request "method not found".
#include "runtime/lsp/features.hpp"

namespace seqc::lsp {

nlohmann::json feature_capabilities() { return nlohmann::json::object(); }

std::optional<nlohmann::json> answer_feature(std::string_view /*method*/,
                                             const nlohmann::json& /*params*/,
                                             FeatureContext& /*ctx*/) {
  return std::nullopt;
}

}  // namespace seqc::lsp
