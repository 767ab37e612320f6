#pragma once
// Helpers shared by the differential stages.

#include <algorithm>
#include <string>

#include "pcsketch/core/error.h"
#include "pcsketch/neighbourhood/neighbourhoods.h"

namespace pcsketch::differential::detail {

/// Neighbours a stage uses: `requested`, or all of the shared neighbourhood when 0 (never more than it holds).
inline std::size_t neighbours_used(std::size_t requested, const neighbourhood::Neighbourhoods& neighbourhoods) {
  return requested == 0 ? neighbourhoods.k : std::min(requested, neighbourhoods.k);
}

/// Throws unless the neighbourhoods were computed for these `count` points.
inline void check_neighbourhoods(std::string_view stage, std::size_t count,
                                 const neighbourhood::Neighbourhoods& neighbourhoods) {
  const bool trivial = neighbourhoods.k == 0 && neighbourhoods.indices.empty() && count <= 1;
  if (neighbourhoods.size() != count && !trivial)
    throw Error(std::string(stage) + ": the neighbourhoods cover " + std::to_string(neighbourhoods.size()) +
                " points but the cloud has " + std::to_string(count));
}

}  // namespace pcsketch::differential::detail
