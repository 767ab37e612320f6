#include "pcsketch/neighbourhood/spacing.h"

#include <algorithm>

namespace pcsketch::neighbourhood {

float mean_spacing(const Neighbourhoods& neighbourhoods) {
  const std::size_t n = neighbourhoods.size();
  std::vector<float> nearest;
  nearest.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    // Nearest neighbour at a non-zero distance: duplicates would drive h to 0.
    for (float d : neighbourhoods.distances_of(i)) {
      if (d > 0) {
        nearest.push_back(d);
        break;
      }
    }
  }
  if (nearest.empty()) return 0.f;
  // Drop the 1% largest values (isolated outliers); keep at least one.
  const std::size_t kept = std::max<std::size_t>(1, nearest.size() - nearest.size() / 100);
  std::nth_element(nearest.begin(), nearest.begin() + (kept - 1), nearest.end());
  double sum = 0;
  for (std::size_t i = 0; i < kept; ++i) sum += nearest[i];
  return static_cast<float>(sum / static_cast<double>(kept));
}

}  // namespace pcsketch::neighbourhood
