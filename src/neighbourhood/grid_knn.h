#pragma once
// Exact k-NN of every point of a cloud over a uniform grid, for the points whose answer the grid can prove.

#include <cstdint>
#include <vector>

#include "pcsketch/core/point_cloud.h"
#include "pcsketch/core/report.h"

namespace pcsketch::neighbourhood::detail {

/// Fills row i (k entries at indices + i*k, distances + i*k) with the k nearest points to point i, self excluded by
/// index, nearest first, ties in index order: the same rows as KdTree::knn_of_point, bit for bit. The cell edge is
/// chosen from the cloud so that a cell holds about k/2 points; a row is filled only when its k-th distance is
/// provably shorter than the way out of the 27 cells around the point's own, so that no point outside them can
/// belong to the row. The points left (sparse regions, isolated points, crowded cells) are returned in increasing
/// order, their rows untouched. Requires k ≥ 1 and points.size() > k.
std::vector<std::uint32_t> grid_knn(const std::vector<Vec3f>& points, std::size_t k, std::uint32_t* indices,
                                    float* distances, const ProgressFn& progress);

}  // namespace pcsketch::neighbourhood::detail
