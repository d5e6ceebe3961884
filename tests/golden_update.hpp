// The one rule for rewriting golden files: they are rewritten instead of compared when, and
// only when, the environment has SEQC_UPDATE_GOLDEN=1 (any other value compares as usual).
// Review every rewritten file by eye before committing it.
#pragma once

#include <cstdlib>
#include <cstring>

namespace seqc::testing {

inline bool updating_goldens() {
  const char* v = std::getenv("SEQC_UPDATE_GOLDEN");
  return v != nullptr && std::strcmp(v, "1") == 0;
}

}  // namespace seqc::testing
