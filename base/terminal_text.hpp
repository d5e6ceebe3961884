// Text from a file (a name, a key, a path) made safe to show on a terminal. A choreography can
// hold any character in a quoted YAML value, and a terminal acts on some of them: ESC starts a
// sequence that moves the cursor, recolours or retitles the window, a newline or a carriage
// return can forge a whole diagnostic line. Every value seqc quotes in text meant for a person
// (diagnostics, notes, listings, summaries) passes through terminal_safe().
#pragma once

#include <string>
#include <string_view>

namespace seqc {

// `text` with every control character shown as an escape, so nothing but its printable
// characters reaches a terminal: the C0 controls other than tab and DEL as \n, \r and \xNN
// (ESC is \x1b), the C1 controls (U+0080..U+009F, which some terminals obey like ESC
// sequences) as \u0080..\u009f, and a byte that is not part of valid UTF-8 as \xNN. Tabs,
// printable ASCII (the backslash included, unchanged) and the rest of valid UTF-8 are copied.
std::string terminal_safe(std::string_view text);

}  // namespace seqc
