// The on-curve search: the fewest actions through a stretch whose every target is the rounded
// curve, each servo within its band at every millisecond (exact, a dynamic program over
// boundaries). It gives up (Path::gave_up) past kWorkBudget, and where no sequence reaches the
// end it returns the actions to the farthest boundary any reaches (the shortfall is there).
#pragma once

#include <cstddef>

#include "compiler/fitting/stretch.hpp"

namespace seqc::compiler::fitting {

Path on_curve_search(const Stretch& in, const SearchLimits& lim, std::size_t first,
                     std::size_t last, std::size_t& work);

}  // namespace seqc::compiler::fitting
