// How the language front end reports mistakes: through Diagnostics, once per place and message
// (a pose used in a loop is wrong once, not once per iteration), with a note for every
// performance of a section with parameters the mistake is inside (its values explain it), a
// "used here" note at every alias that copied the node the mistake is said at, for a
// warning inside a plain section a note at the `- section:` step that performed it, and an
// "included from here" note for every include that led to the file the mistake is in. An error
// that stops the walk (a budget passed) names the whole chain: every performance and include.
#pragma once

#include <initializer_list>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>
#include <vector>

#include "base/diagnostics.hpp"
#include "compiler/frontend/yaml/yaml_tree.hpp"

namespace seqc::compiler {

class Reporter {
 public:
  explicit Reporter(Diagnostics& diags) : diags_(diags) {}

  // `note`, if given, follows the diagnostic (e.g. where a pose with a bad value was used).
  struct Note {
    Location at;
    std::string message;
  };
  void error(Location at, std::string message, std::optional<Note> note = {}) {
    report(Severity::Error, at, std::move(message), std::move(note));
  }
  void warning(Location at, std::string message, std::optional<Note> note = {}) {
    report(Severity::Warning, at, std::move(message), std::move(note));
  }
  // An error followed by each of `notes` (then the notes of the running performances and
  // includes, as for any error).
  void error(Location at, std::string message, std::vector<Note> notes) {
    report(Severity::Error, at, std::move(message), std::move(notes));
  }
  // A note on its own: what the check assumed where it could not know (printed once).
  void note(Location at, std::string message) {
    report(Severity::Note, at, std::move(message), std::nullopt);
  }

  // While a section with parameters is performed: every diagnostic gets `note` (innermost
  // performance first).
  void push_context(Note note) { performing_.push_back({std::move(note), true}); }
  void pop_context() { performing_.pop_back(); }

  // The include sites (outermost first) of the file being lowered.
  void push_include(Location site) { includes_.push_back(site); }
  void pop_include() { includes_.pop_back(); }
  // Where aliases copied nodes (kept by the caller, who outlives this reporter); without it, no
  // "used here" notes.
  void set_alias_uses(const AliasUses* uses) { alias_uses_ = uses; }
  const std::vector<Location>& include_sites() const { return includes_; }
  void set_include_sites(std::vector<Location> sites) { includes_ = std::move(sites); }
  // The `- section:` steps performing the steps being lowered (outermost first): a warning
  // raised inside a section names its performance with a note, since the section's own lines
  // are the same each time it is performed.
  void push_performance(Location site, const std::string& name) {
    performing_.push_back({{site, "in section '" + name + "', performed here"}, false});
  }
  void pop_performance() { performing_.pop_back(); }
  // A repeat's pass (counted from 1), named only by chain(): a warning inside a repeat is the
  // same at every pass, but an error that stops the walk says which pass it reached.
  void push_pass(Location repeat, long long pass, long long times) {
    performing_.push_back({{repeat, "in pass " + std::to_string(pass) + " of " +
                                        std::to_string(times) + " of this repeat"},
                           false,
                           true});
  }
  void pop_pass() { performing_.pop_back(); }
  // Everything that led to the steps being lowered, innermost first: each section's
  // performance (with its values, if any) and each include. An error that stops the walk
  // names the whole chain, also when it is reported once the walk has left it.
  std::vector<Note> chain() const;
  // An error followed by exactly `notes` (nothing added from the running performances and
  // includes, which `notes` usually holds already: see chain()).
  void error_with_notes(Location at, std::string message, const std::vector<Note>& notes);
  std::size_t errors_reported() const { return errors_; }
  std::size_t include_depth() const { return includes_.size(); }

  // Reports every key of `map` that is not in `allowed`, with "did you mean". True if all known.
  bool check_keys(const YamlNode& map, std::initializer_list<std::string_view> allowed,
                  std::string_view where) {
    return check_keys(map, std::span<const std::string_view>(allowed.begin(), allowed.size()),
                      where);
  }
  bool check_keys(const YamlNode& map, std::span<const std::string_view> allowed,
                  std::string_view where);

  // `name` and `description` are free text: a list or map there is an error.
  void check_free_text(const YamlNode& root);

  // "unknown X 'word'; did you mean 'y'?" (the suggestion only when one is close). `known`, if
  // given, lists the valid names after it: "(robots: xarm, lsc-16, ...)".
  void unknown(Location at, std::string_view what, std::string_view word,
               const std::vector<std::string>& candidates, std::string_view where = {},
               std::string_view known = {});

 private:
  void report(Severity severity, Location at, std::string message, std::optional<Note> note) {
    std::vector<Note> notes;
    if (note) notes.push_back(std::move(*note));
    report(severity, at, std::move(message), std::move(notes));
  }
  void report(Severity severity, Location at, std::string message, std::vector<Note> notes);
  void note_alias_uses(Location at);

  Diagnostics& diags_;
  std::vector<Location> includes_;
  // The running performances, outermost first; `with_values`: a performance with parameters,
  // whose note every diagnostic gets (the others' only warnings).
  struct Performance {
    Note note;
    bool with_values = false;
    bool pass = false;  // a repeat's pass: in chain() only
  };
  std::vector<Performance> performing_;
  const AliasUses* alias_uses_ = nullptr;
  std::size_t errors_ = 0;
  std::set<std::tuple<int, std::uint32_t, std::uint32_t, std::uint32_t, std::string>> seen_;
};

}  // namespace seqc::compiler
