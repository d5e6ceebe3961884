#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <utility>
#include <vector>

#include "compiler/fitting/free_search.hpp"
#include "compiler/fitting/free_targets.hpp"

namespace seqc::compiler::fitting {

// The joint free fit's work is capped at kJointWorkFactor x the on-curve fit's + kJointWorkFloor
// (its units are dearer, a window per start value rather than per servo); past that the search
// is dropped and the on-curve fit kept.
constexpr std::size_t kJointWorkFactor = 2;
// The work the grid is chosen for, per unit of the on-curve fit's (see joint_grid()).
constexpr double kJointGridTarget = 0.75;
// The coarsest grid of boundaries the joint free fit tries (see joint_grid()).
constexpr std::size_t kMaxGrid = 8;
// Work any joint search may spend whatever the on-curve fit spent: about a tenth of a
// millisecond, so that short stretches (a few hundred ms of a few servos) are searched on every
// millisecond, where a coarser grid costs actions and the finer one costs no time worth having.
constexpr std::size_t kJointWorkFloor = 60'000;
// Labels of the free fit kept per boundary when several servos share it (see free_joint_search()).
constexpr std::size_t kBeamBest = 2;  // with the fewest actions
constexpr std::size_t kBeamNext = 1;  // with one more (a way round dead ends near the end)

namespace {

// The value of `set` (bits from `low`) nearest servo i's curve at t.
int nearest(const Stretch& in, std::size_t i, std::size_t t, std::uint64_t set, int low) {
  int pick = low;
  double off = 1e300;
  for (std::uint64_t bits = set; bits != 0; bits &= bits - 1) {
    const int v = low + std::countr_zero(bits);
    const double d = std::abs(v - in.want[in.at(i, t)]);
    if (d < off) {
      off = d;
      pick = v;
    }
  }
  return pick;
}

// How far the line from u at s to v at e leaves servo i's band between them (<= 0: never).
double line_over(const Stretch& in, std::size_t i, std::size_t s, std::size_t e, int u, int v) {
  double most = -1e300;
  const double span = static_cast<double>(e - s);
  for (std::size_t t = s + 1; t < e; ++t) {
    const double line = u + (v - u) * static_cast<double>(t - s) / span;
    const std::size_t x = in.at(i, t);
    most = std::max({most, in.lo[x] - line, line - in.hi[x]});
  }
  return most;
}

struct Label {
  int key = kNoKey;
  std::size_t parent = 0;  // label index
  int width = 0;           // the sizes of the sets, summed
  std::size_t t = 0;       // its boundary (ms from the stretch's start)
};

}  // namespace

// The work the joint free fit may spend after the on-curve fit spent `on`: a few times as
// much, so that compiling stays within about twice the on-curve fit's time.
std::size_t joint_cap(std::size_t on) { return kJointWorkFactor * on + kJointWorkFloor; }

// The boundaries the joint free fit tries: every grid-th ms (and every knot), the grid as
// fine as the cap allows. Its work per candidate end is a window per start value, about
// (the band's width) x the on-curve fit's window per servo.
std::size_t joint_grid(const Stretch& in, std::size_t first, std::size_t last, std::size_t on) {
  double width = 0;
  std::size_t samples = 0;
  for (std::size_t i = 0; i < in.k; ++i) {
    for (std::size_t t = first; t <= last; t += 1 + (last - first) / 16) {
      width += std::max(1, in.vhi[in.at(i, t)] - in.vlo[in.at(i, t)] + 1);
      ++samples;
    }
  }
  const double expected = static_cast<double>(on) * width / static_cast<double>(samples);
  const double allowed = kJointGridTarget * static_cast<double>(on) + kJointWorkFloor;
  return std::clamp<std::size_t>(static_cast<std::size_t>(std::ceil(expected / allowed)), 1,
                                 kMaxGrid);
}

// The free fit for several curved servos sharing boundaries. Their joint states are too
// many to search exactly ((2 x tolerance + 1)^servos per ms), so a label at a boundary holds,
// per servo, the SET of whole units it can reach there along one sequence of boundaries (the
// servos' lines are independent once the boundaries are fixed, so the sets are exact for that
// sequence). A boundary keeps a few labels that no other dominates (as few actions and every
// set as large): kBeamBest with its fewest actions and kBeamNext with one more, which gets
// round dead ends where the fewest-action labels' sets cannot go on. Only fits with a key
// below `bound` (the on-curve fit's) are looked for.
Path free_joint_search(const Stretch& in, const SearchLimits& lim, std::size_t first,
                       std::size_t last, int bound, std::size_t grid, std::size_t cap,
                       std::size_t& work) {
  const std::size_t k = in.k;
  const std::size_t min = lim.min_ms, max = lim.max_ms;
  const std::size_t len = last - first + 1;
  std::vector<Label> labels;
  std::vector<std::uint64_t> sets;  // k per label, bits from each servo's low end at its t
  std::vector<std::vector<std::size_t>> at(len);
  std::vector<int> best_count(len, kNoKey);
  std::vector<int> low(len * k), high(len * k);
  for (std::size_t t = first; t <= last; ++t) {
    for (std::size_t i = 0; i < k; ++i) {
      std::tie(low[(t - first) * k + i], high[(t - first) * k + i]) = free_band(in, i, t, last);
    }
  }
  for (std::size_t i = 0; i < k; ++i) low[i] = high[i] = in.pin[in.at(i, first)];
  labels.push_back({0, 0, static_cast<int>(k), first});
  sets.insert(sets.end(), k, 1);
  at[0].push_back(0);
  best_count[0] = 0;
  int best_end = kNoKey;  // the smallest key at `last`
  // Per boundary: how wide a label holding every target of every servo is, and the smallest
  // key of such a label there (no later label with a key as large can enter).
  std::vector<int> full_width(len, 0), full_key(len, kNoKey);
  for (std::size_t t = 0; t < len; ++t) {
    for (std::size_t i = 0; i < k; ++i) {
      full_width[t] += std::max(0, high[t * k + i] - low[t * k + i] + 1);
    }
  }

  // Adds a label at e unless one there dominates it; drops those it dominates; keeps the beam.
  std::vector<std::uint64_t> cand(k);
  auto covers = [&](const std::uint64_t* x, const std::uint64_t* y) {
    for (std::size_t i = 0; i < k; ++i) {
      if ((x[i] & y[i]) != y[i]) return false;
    }
    return true;
  };
  // Labels dropped from a boundary before it was expanded have no children: their slots are
  // used again.
  std::vector<std::size_t> spare;
  auto drop = [&](std::size_t id) { spare.push_back(id); };
  auto insert = [&](std::size_t e, int key, std::size_t parent) {
    const int count = key / 2;
    int& best = best_count[e - first];
    if (best != kNoKey && count > best + 1) return;
    std::vector<std::size_t>& here = at[e - first];
    int width = 0;
    for (std::uint64_t c : cand) width += std::popcount(c);
    // Not taken when one there dominates it, or when its count's beam is full of labels no
    // worse than it.
    std::size_t same_level = 0;
    bool beats_one = false;
    for (std::size_t id : here) {
      const Label& l = labels[id];
      if (l.key <= key && covers(&sets[id * k], cand.data())) return;
      if (l.key / 2 != count) continue;
      ++same_level;
      beats_one = beats_one || key < l.key || (key == l.key && width > l.width) ||
                  covers(cand.data(), &sets[id * k]);
    }
    const int level_best = best == kNoKey ? count : std::min(best, count);
    const std::size_t keep = count == level_best ? kBeamBest : kBeamNext;
    if (same_level >= keep && !beats_one) return;
    std::erase_if(here, [&](std::size_t id) {
      const bool dominated = key <= labels[id].key && covers(cand.data(), &sets[id * k]);
      if (dominated) drop(id);
      return dominated;
    });
    if (width == full_width[e - first]) full_key[e - first] = std::min(full_key[e - first], key);
    std::size_t id = labels.size();
    if (!spare.empty()) {
      id = spare.back();
      spare.pop_back();
      labels[id] = {key, parent, width, e};
      std::copy(cand.begin(), cand.end(), sets.begin() + static_cast<std::ptrdiff_t>(id * k));
    } else {
      labels.push_back({key, parent, width, e});
      sets.insert(sets.end(), cand.begin(), cand.end());
    }
    here.push_back(id);
    best = std::min(best, count);
    if (e == last) best_end = std::min(best_end, key);
    // The beam: at each of the two counts, the labels with the smallest keys, widest first.
    std::erase_if(here, [&](std::size_t x) {
      const bool out = labels[x].key / 2 > best + 1;
      if (out) drop(x);
      return out;
    });
    for (int level : {best, best + 1}) {
      const std::size_t level_keep = level == best ? kBeamBest : kBeamNext;
      for (;;) {
        std::size_t count_here = 0, worst = 0;
        for (std::size_t x : here) {
          if (labels[x].key / 2 != level) continue;
          if (count_here++ == 0 || labels[x].key > labels[worst].key ||
              (labels[x].key == labels[worst].key && labels[x].width < labels[worst].width)) {
            worst = x;
          }
        }
        if (count_here <= level_keep) break;
        std::erase(here, worst);
        drop(worst);
      }
    }
  };

  // The windows of one expansion: one per servo and start value in any label at s.
  // Laid out per servo (index base[i] + bit), so that the window updates run in straight
  // loops: they are most of the search's time.
  std::vector<double> su, slo, shi;
  std::vector<std::size_t> soff;           // where each start's servo's samples begin
  std::vector<std::uint64_t> sreach;       // the targets each reaches at the current end
  std::vector<std::size_t> base(k + 1);    // each servo's first start
  std::vector<std::uint64_t> open_set(k);  // each servo's starts still open, by bit
  const std::vector<double>& inv = *lim.inverse;
  std::vector<std::size_t> live;
  auto on_grid = [&](std::size_t t) {
    return grid == 1 || (t - first) % grid == 0 || t == last || in.is_knot[t] != 0;
  };
  for (std::size_t s = first; s < last; ++s) {
    live.clear();
    const int limit = std::min(bound, best_end);
    for (std::size_t id : at[s - first]) {
      if (labels[id].key + 2 < limit) live.push_back(id);
    }
    if (live.empty() || !on_grid(s)) continue;
    su.clear();
    soff.clear();
    slo.clear();
    shi.clear();
    for (std::size_t i = 0; i < k; ++i) {
      std::uint64_t all = 0;
      for (std::size_t id : live) all |= sets[id * k + i];
      base[i] = su.size();
      const int ls = low[(s - first) * k + i];
      for (int b = 0; b < 64; ++b) {
        // Every bit up to the highest is given a start, so that a start's index is its bit.
        if ((all >> b) == 0) break;
        su.push_back(ls + b);
        soff.push_back(in.at(i, 0));
        slo.push_back(-1e300);
        shi.push_back((all >> b & 1) != 0 ? 1e300 : -1e301);
      }
    }
    base[k] = su.size();
    sreach.resize(su.size());
    std::size_t open_count = 0;
    for (std::size_t j = 0; j < su.size(); ++j) open_count += slo[j] <= shi[j] ? 1 : 0;
    const std::size_t stop = std::min({last, s + max, std::size_t{in.next_knot[s]}});
    for (std::size_t e = s + 1; e <= stop; ++e) {
      work += su.size();
      if (work > cap) return Path{};  // dearer than the time it may save: on-curve stays
      const double span = static_cast<double>(e - s), r = inv[e - s];
      // A label with one action more than the fewest only helps near the end, where the
      // shortest action's floor leaves dead ends.
      const int be = best_count[e - first];
      const int slack = last - e < 3 * min ? 1 : 0;
      auto wanted = [&](int key) {
        return (be == kNoKey || key / 2 + 1 <= be + slack) && key + 2 < full_key[e - first];
      };
      if (e - s >= min && on_grid(e)) {
        bool any = false;
        for (std::size_t id : live) any = any || wanted(labels[id].key);
        if (any) {
          for (std::size_t i = 0; i < k; ++i) {
            const std::size_t x = (e - first) * k + i;
            for (std::size_t j = base[i]; j < base[i + 1]; ++j) {
              sreach[j] = slo[j] <= shi[j] ? reachable(static_cast<int>(su[j]), slo[j], shi[j],
                                                       span, low[x], high[x])
                                           : 0;
            }
          }
          for (std::size_t id : live) {
            const int key = labels[id].key;
            if (!wanted(key)) continue;
            bool all = true;
            for (std::size_t i = 0; i < k && all; ++i) {
              std::uint64_t c = 0;
              for (std::uint64_t bits = sets[id * k + i]; bits != 0; bits &= bits - 1) {
                c |= sreach[base[i] + static_cast<std::size_t>(std::countr_zero(bits))];
              }
              cand[i] = c;
              all = c != 0;
            }
            if (!all) continue;
            if (s != first) {
              insert(e, key + 2, id);
              continue;
            }
            // A first action that moves nothing costs a half more: offer the label without
            // the non-moving choice of the servo that can move most, and the whole label at
            // the higher key when every servo can stay.
            std::size_t widest = k;
            int most = 0;
            bool all_still = true;
            for (std::size_t i = 0; i < k; ++i) {
              const int p = low[i], ls = low[(e - first) * k + i];
              const std::uint64_t still = p >= ls && p - ls < 64 ? std::uint64_t{1} << (p - ls) : 0;
              const int moving = std::popcount(cand[i] & ~still);
              if (moving > most) {
                most = moving;
                widest = i;
              }
              all_still = all_still && (cand[i] & still) != 0;
            }
            const std::vector<std::uint64_t> whole = cand;
            if (widest < k) {
              const int p = low[widest], ls = low[(e - first) * k + widest];
              if (p >= ls && p - ls < 64) cand[widest] &= ~(std::uint64_t{1} << (p - ls));
              insert(e, key + 2, id);
            }
            if (all_still) {
              cand = whole;
              insert(e, key + 3, id);
            }
          }
        }
      }
      std::size_t still_open = 0;
      for (std::size_t j = 0; j < su.size(); ++j) {
        const std::size_t x = soff[j] + e;
        slo[j] = std::max(slo[j], (in.lo[x] - su[j]) * r);
        shi[j] = std::min(shi[j], (in.hi[x] - su[j]) * r);
        still_open += slo[j] <= shi[j] ? 1 : 0;
      }
      if (still_open == open_count) continue;
      open_count = still_open;
      for (std::size_t i = 0; i < k; ++i) {
        std::uint64_t open = 0;
        for (std::size_t j = base[i]; j < base[i + 1]; ++j) {
          open |= static_cast<std::uint64_t>(slo[j] <= shi[j]) << (j - base[i]);
        }
        open_set[i] = open;
      }
      // A label goes on while each of its servos has a start still open.
      std::erase_if(live, [&](std::size_t id) {
        for (std::size_t i = 0; i < k; ++i) {
          if ((sets[id * k + i] & open_set[i]) == 0) return true;
        }
        return false;
      });
      if (live.empty()) break;
    }
  }
  // The end: the label with the fewest actions at `last`, or at the farthest boundary.
  std::size_t t = last;
  if (at[last - first].empty()) {
    if (bound != kNoKey) return Path{};  // nothing better than the on-curve fit
    std::vector<int> reached(len, kNoKey);
    for (std::size_t x = 0; x < len; ++x) {
      if (!at[x].empty()) reached[x] = 0;
    }
    t = farthest_reached(in, reached, first, last, min);
  }
  Path path;
  path.complete = t == last;
  path.reached = t;
  if (t == first) {
    path.key = 4 * static_cast<int>(last - first);
    return path;
  }
  std::size_t id = at[t - first].front();
  for (std::size_t x : at[t - first]) {
    if (labels[x].key < labels[id].key) id = x;
  }
  path.key = labels[id].key + (path.complete ? 0 : 4 * static_cast<int>(last - t));
  // Back from the end: each servo's target there (nearest the curve), then at each earlier
  // boundary a value of the parent's set from which the line to the later target fits.
  std::vector<std::size_t> chain;
  for (std::size_t x = id; x != 0; x = labels[x].parent) chain.push_back(x);
  std::vector<int> later(k);
  for (std::size_t i = 0; i < k; ++i) {
    later[i] = nearest(in, i, t, sets[id * k + i], low[(t - first) * k + i]);
  }
  path.ends.resize(chain.size());
  path.values.resize(chain.size() * k);
  for (std::size_t c = 0; c < chain.size(); ++c) {
    const std::size_t pos = chain.size() - 1 - c;
    const std::size_t e = labels[chain[c]].t, parent = labels[chain[c]].parent;
    const std::size_t s = labels[parent].t;
    path.ends[pos] = e;
    std::copy(later.begin(), later.end(),
              path.values.begin() + static_cast<std::ptrdiff_t>(pos * k));
    for (std::size_t i = 0; i < k; ++i) {
      const int ls = low[(s - first) * k + i];
      int pick = ls;
      double pick_over = 1e300, pick_off = 1e300;
      for (std::uint64_t bits = sets[parent * k + i]; bits != 0; bits &= bits - 1) {
        const int u = ls + std::countr_zero(bits);
        const double over = line_over(in, i, s, e, u, later[i]);
        const double off = std::abs(u - in.want[in.at(i, s)]);
        if (std::max(over, 0.0) < std::max(pick_over, 0.0) ||
            (std::max(over, 0.0) == std::max(pick_over, 0.0) && off < pick_off)) {
          pick = u;
          pick_over = over;
          pick_off = off;
        }
      }
      later[i] = pick;
    }
  }
  return path;
}

}  // namespace seqc::compiler::fitting
