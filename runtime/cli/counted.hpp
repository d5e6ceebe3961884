// A count with its noun, as every summary line words it: "1 action", "27 actions".
#pragma once

#include <cstddef>
#include <string>

#include <fmt/format.h>

namespace seqc::cli {

inline std::string plural(std::size_t n, const char* word) {
  return fmt::format("{} {}{}", n, word, n == 1 ? "" : "s");
}

}  // namespace seqc::cli
