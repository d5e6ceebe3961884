#include "compiler/fitting/search_memo.hpp"

#include <bit>

namespace seqc::compiler::fitting {

namespace {

// A hash of the stretch's length, servos and intended positions: the other samples mostly
// follow from these, and same_content() compares them all.
std::uint64_t content_hash(const Stretch& in) {
  std::uint64_t h = (in.n * 0x9e3779b97f4a7c15ULL ^ in.k) + std::bit_cast<std::uint64_t>(in.step);
  for (const double w : in.want) {
    h = (h ^ std::bit_cast<std::uint64_t>(w)) * 0xff51afd7ed558ccdULL;
    h ^= h >> 32;
  }
  return h;
}

// Everything a search reads is equal.
bool same_content(const Stretch& x, const Stretch& y) {
  return x.n == y.n && x.step == y.step && x.k == y.k && x.want == y.want && x.lo == y.lo &&
         x.hi == y.hi && x.tol == y.tol && x.pin == y.pin && x.vlo == y.vlo && x.vhi == y.vhi &&
         x.pinned == y.pinned && x.next_knot == y.next_knot && x.is_knot == y.is_knot;
}

}  // namespace

void SearchMemo::enter(const Stretch& in, StretchSource source, const Sampler& sample) {
  const std::uint64_t hash = content_hash(in);
  const auto [from, to] = by_hash_.equal_range(hash);
  for (auto it = from; it != to; ++it) {
    Searched& earlier = stretches_[it->second];
    if (same_content(sample(earlier.source), in)) {
      current_ = earlier.searches.get();
      return;
    }
  }
  by_hash_.emplace(hash, stretches_.size());
  stretches_.push_back({std::move(source), std::make_unique<Searches>()});
  current_ = stretches_.back().searches.get();
}

const std::pair<Path, std::size_t>* SearchMemo::find(const SearchKey& key) const {
  const auto it = current_->find(key);
  return it == current_->end() ? nullptr : &it->second;
}

void SearchMemo::store(const SearchKey& key, const Path& path, std::size_t work) {
  current_->emplace(key, std::make_pair(path, work));
}

}  // namespace seqc::compiler::fitting
