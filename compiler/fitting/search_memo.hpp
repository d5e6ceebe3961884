// The searches already run while fitting one timeline, by the content of the stretch each ran
// on, private to compiler/fitting: a search asked again of the same part of an equal stretch
// (the on-curve refit of fit_stretch(), a repeat, a section performed again, another servo
// making the same move) is answered with the Path it found and the work it spent, so that it
// runs once. Equal means equal in everything a search reads (a stretch's place in time is not
// read); a stretch is told from others by a hash and, where the hash matches, compared whole
// with the earlier one sampled again, so that the stretches themselves need not be kept.
#pragma once

#include <compare>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <unordered_map>
#include <utility>
#include <vector>

#include "compiler/fitting/stretch.hpp"

namespace seqc::compiler::fitting {

enum class SearchKind : std::uint8_t { OnCurve, FreeSingle, FreeJoint };

// One search of a stretch: which, over which part [first, last], and its limits.
struct SearchKey {
  SearchKind kind = SearchKind::OnCurve;
  std::size_t first = 0, last = 0;
  int bound = kNoKey;
  std::size_t grid = 0, cap = 0;
  auto operator<=>(const SearchKey&) const = default;
};

// Where a stretch was sampled from: its curved servos, its first knot and the knots after it.
struct StretchSource {
  std::vector<std::size_t> curved;
  std::int64_t a = 0;
  std::vector<std::int64_t> inner;
};

class SearchMemo {
 public:
  using Sampler = std::function<Stretch(const StretchSource&)>;

  // Makes `in` (sampled from `source`) the current stretch: its searches are those run on an
  // equal stretch before, if any (`sample` samples an earlier one again to compare).
  void enter(const Stretch& in, StretchSource source, const Sampler& sample);

  // A search of the current stretch run before: its Path and work (nullptr: not run).
  const std::pair<Path, std::size_t>* find(const SearchKey& key) const;
  void store(const SearchKey& key, const Path& path, std::size_t work);

 private:
  using Searches = std::map<SearchKey, std::pair<Path, std::size_t>>;
  struct Searched {
    StretchSource source;
    std::unique_ptr<Searches> searches;
  };
  std::vector<Searched> stretches_;
  std::unordered_multimap<std::uint64_t, std::size_t> by_hash_;  // into stretches_
  Searches* current_ = nullptr;
};

}  // namespace seqc::compiler::fitting
