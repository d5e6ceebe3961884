// Stable rule ids for diagnostics, for machine-readable output (`seqc check --format
// json|sarif`): every message seqc prints falls into one kind ("unknown-key",
// "out-of-limits", ...). The kind is read from the message's wording in one table, so the
// ~130 places that report a mistake stay as they are; a new message that matches no row gets
// the generic "invalid-value" and the rules test lists it.
#pragma once

#include <string_view>
#include <vector>

#include "base/diagnostics.hpp"

namespace seqc {

struct DiagnosticRule {
  std::string_view id;     // "unknown-key"
  std::string_view title;  // "Unknown key"
  std::string_view help;   // one sentence: what the rule catches
};

const std::vector<DiagnosticRule>& diagnostic_rules();

// The rule of a diagnostic (notes take the rule of what they annotate; pass that one).
const DiagnosticRule& rule_for(const Diagnostic& d);

}  // namespace seqc
