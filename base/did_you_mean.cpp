#include <algorithm>
#include <cctype>
#include <string>
#include <string_view>
#include <vector>

#include "base/diagnostics.hpp"

namespace seqc {

namespace {

char lower(char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); }

// Optimal-string-alignment distance (Levenshtein plus adjacent transposition), so "tmie" is one
// edit from "time" like "tme" is.
std::size_t edit_distance(std::string_view a, std::string_view b, bool fold_case) {
  auto eq = [fold_case](char x, char y) { return fold_case ? lower(x) == lower(y) : x == y; };
  const std::size_t n = a.size();
  const std::size_t m = b.size();
  std::vector<std::size_t> prev2(m + 1), prev(m + 1), cur(m + 1);
  for (std::size_t j = 0; j <= m; ++j) prev[j] = j;
  for (std::size_t i = 1; i <= n; ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t cost = eq(a[i - 1], b[j - 1]) ? 0 : 1;
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + cost});
      if (i > 1 && j > 1 && eq(a[i - 1], b[j - 2]) && eq(a[i - 2], b[j - 1])) {
        cur[j] = std::min(cur[j], prev2[j - 2] + 1);
      }
    }
    std::swap(prev2, prev);
    std::swap(prev, cur);
  }
  return prev[m];
}

}  // namespace

// Threshold max(1, len/3): one typo in a short key, a few in a long one, but never a
// suggestion that shares little with what was written. Ranking: case-insensitive distance,
// then case-sensitive distance, then the alphabetically first candidate, so the answer does
// not depend on the order the candidates were listed in.
std::string did_you_mean(std::string_view word, const std::vector<std::string>& candidates) {
  if (word.empty()) return {};
  const std::size_t limit = std::max<std::size_t>(1, word.size() / 3);
  const std::string* best = nullptr;
  std::size_t best_folded = 0;
  std::size_t best_exact = 0;
  for (const std::string& c : candidates) {
    const std::size_t diff =
        c.size() > word.size() ? c.size() - word.size() : word.size() - c.size();
    if (diff > limit || c == word) continue;
    const std::size_t folded = edit_distance(word, c, true);
    if (folded > limit) continue;
    const std::size_t exact = edit_distance(word, c, false);
    if (best == nullptr || folded < best_folded ||
        (folded == best_folded && (exact < best_exact || (exact == best_exact && c < *best)))) {
      best = &c;
      best_folded = folded;
      best_exact = exact;
    }
  }
  return best != nullptr ? *best : std::string();
}

}  // namespace seqc
