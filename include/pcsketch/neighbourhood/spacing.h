#pragma once
// The mean point spacing h: the unit every default length of the pipeline is a multiple of.

#include "pcsketch/neighbourhood/neighbourhoods.h"

namespace pcsketch::neighbourhood {

/// Mean distance from a point to its nearest neighbour, ignoring duplicates (distance 0) and the 1% largest values
/// (isolated outliers would otherwise inflate h). Returns 0 for clouds with fewer than 2 distinct points.
float mean_spacing(const Neighbourhoods& neighbourhoods);

}  // namespace pcsketch::neighbourhood
