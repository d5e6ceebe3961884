// The free-end-point searches: the fewest actions through a stretch whose targets between the
// servos' own knots may be any whole unit within tolerance and limits. For one curved servo the
// search is exact and, among fits with as few actions, takes one with every target on the
// rounded curve where there is one; for several, a label per boundary holds each servo's set of
// reachable end values, a small beam of labels that no other dominates is kept, and the
// boundaries tried may be a coarser grid (joint_grid()) with the work capped (joint_cap()). Both
// look only for fits with a key below `bound` (an on-curve fit's, the on-curve search's or the
// greedy walk's of greedy_on_curve_key(); kNoKey: any), return an empty incomplete Path when
// there is none, and give up (Path::gave_up) past their budget.
#pragma once

#include <cstddef>

#include "compiler/fitting/stretch.hpp"

namespace seqc::compiler::fitting {

Path free_single_search(const Stretch& in, const SearchLimits& lim, std::size_t first,
                        std::size_t last, int bound, std::size_t& work);

// The key of the on-curve fit of one curved servo taken greedily (each action to the farthest
// boundary its line reaches that leaves room for the next; kNoKey where that gets stuck): a
// bound for free_single_search() that costs one pass over the stretch.
int greedy_on_curve_key(const Stretch& in, const SearchLimits& lim, std::size_t first,
                        std::size_t last);

Path free_joint_search(const Stretch& in, const SearchLimits& lim, std::size_t first,
                       std::size_t last, int bound, std::size_t grid, std::size_t cap,
                       std::size_t& work);

// The work the joint search may spend after the on-curve search spent `on`.
std::size_t joint_cap(std::size_t on);

// Every how many milliseconds the joint search tries a boundary (knots always), from the work
// the on-curve search spent on [first, last].
std::size_t joint_grid(const Stretch& in, std::size_t first, std::size_t last, std::size_t on);

}  // namespace seqc::compiler::fitting
