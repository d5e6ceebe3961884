#include "base/diagnostic_rules.hpp"

#include <algorithm>
#include <array>
#include <string>

namespace seqc {
namespace {

struct Row {
  DiagnosticRule rule;
  std::vector<std::string_view> wording;  // any of these in the message selects the rule
};

// First match wins, so the narrow wordings come before the broad ones.
const std::vector<Row>& rows() {
  static const std::vector<Row> table = {
      {{"yaml-syntax", "Invalid YAML", "The file is not well-formed YAML."},
       {"invalid YAML", "is not supported", "map key", "map keys", "file is ", "nesting", "alias",
        "anchor", "merge key", "not valid UTF-8", "NUL", "not a text file"}},
      {{"duplicate-key", "Duplicate key", "A key appears twice in the same map."},
       {"duplicate key", "first defined here"}},
      {{"unknown-key", "Unknown key", "A key the language does not define at this place."},
       {"unknown key"}},
      {{"unknown-name", "Unknown name",
        "A robot, servo, pose, section or easing that is not defined."},
       {"unknown robot", "unknown servo", "unknown pose", "unknown section", "unknown easing",
        "unknown profile", "unknown track", "unknown parameter", "has no parameter"}},
      {{"include", "Include problem", "An included file is missing, cyclic or for another robot."},
       {"include", "included from here"}},
      {{"action-budget", "Action budget",
        "The sequence needs more actions than a group holds, or none."},
       {"actions; a group holds", "makes no actions", "only rests"}},
      {{"first-move", "First move speed",
        "A servo's first move may start anywhere in its limits, and from the far end it would "
        "be faster than its max_speed."},
       {"first move of"}},
      {{"speed-limit", "Speed or acceleration limit",
        "A move is faster, or accelerates harder, than the servo allows."},
       {"/s, above", "/s², above", "/s^2, above", "acceleration", "unbounded speed", "peaks at",
        "peak at", "needs at least", "need at least"}},
      {{"fit-tolerance", "Fit tolerance",
        "The controller's actions cannot follow a curve within its tolerance."},
       {"cannot keep", "within"}},
      {{"out-of-limits", "Position out of limits", "A position outside the servo's min..max."},
       {"above its max", "below its min", "limits", "not below max"}},
      {{"timing", "Timing", "A duration that is malformed, too short or in the past."},
       {"is not a time", "has no unit", "time unit", "must be a time", "controller's minimum",
        "shorter than the controller", "in the past", "counts beats", "counts bars",
        "beats per minute", "beats per bar", "needs a 'time'", "past it)", "bar line",
        "write 'bar N'", "past its end"}},
      {{"position", "Position", "A position that is not a number, degree or relative move."},
       {"is not a position", "not a whole number of device units", "no known position",
        "nothing to hold", "positive distance", "from where the robot stands"}},
      {{"structure", "Structure", "A missing key, or a value of the wrong kind."},
       {"missing '", "needs a", "needs one of", "must be a list", "must be a map",
        "takes a pose name", "does one thing", "not a list", "not a map", "a list of steps",
        "out of the 'together'"}},
      {{"unused", "Unused definition", "A section of the main file that nothing performs."},
       {"never performed"}},
      {{"invalid-value", "Invalid value", "A value outside what the language accepts."}, {}},
  };
  return table;
}

}  // namespace

const std::vector<DiagnosticRule>& diagnostic_rules() {
  static const std::vector<DiagnosticRule> list = [] {
    std::vector<DiagnosticRule> out;
    for (const Row& r : rows()) out.push_back(r.rule);
    return out;
  }();
  return list;
}

const DiagnosticRule& rule_for(const Diagnostic& d) {
  for (const Row& r : rows()) {
    for (std::string_view w : r.wording) {
      if (d.message.find(w) != std::string::npos) return r.rule;
    }
  }
  return rows().back().rule;
}

}  // namespace seqc
