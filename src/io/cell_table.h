#pragma once
// Per occupied cell of a voxel grid, the point decimate() keeps (nearest the cell's centre; ties: the smallest
// position, then the first in the file). A flat open-addressing table (linear probing, grown at half load): one
// cache miss per point where std::unordered_map allocates a node per cell, 10x slower on 5M cells.

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <tuple>
#include <utility>
#include <vector>

#include "pcsketch/core/point_cloud.h"

namespace pcsketch::io::detail {

class CellTable {
 public:
  using Key = std::array<std::int32_t, 3>;
  /// Largest cell index along an axis (grids finer than this are thinned in memory instead).
  static constexpr double kMaxIndex = 1 << 30;

  /// `intensity`: the table keeps one float per cell too (the XYZ family's intensity column).
  CellTable(bool normals, bool colors, bool intensity = false)
      : normals_(normals), colors_(colors), intensity_(intensity) {
    resize(1 << 16);
  }

  /// Grows the table now so that `more` offers cannot move it (the slots prefetch() touched stay valid).
  void reserve_for(std::size_t more) {
    while (2 * (size_ + more) > capacity_) resize(2 * capacity_);
  }
  /// Starts loading the first slot `key` probes: offers in batches hide the table's cache misses.
  void prefetch(const Key& key) const { __builtin_prefetch(&entries_[hash(key) & (capacity_ - 1)]); }

  /// A candidate for cell `key`; it replaces the cell's representative when nearer its centre (ties as above).
  void offer(const Key& key, double distance2, const std::array<float, 3>& position, std::uint64_t index,
             const Vec3f& normal, const Rgb8& color, float intensity = 0.f) {
    reserve_for(1);
    std::size_t s = slot(key);
    Entry& e = entries_[s];
    if (e.index == kEmpty) {
      e.key = key;
      ++size_;
    } else if (std::tie(distance2, position, index) >= std::tie(e.distance2, e.position, e.index)) {
      return;
    }
    e.distance2 = distance2;
    e.position = position;
    e.index = index;
    if (normals_) normals_of_[s] = normal;
    if (colors_) colors_of_[s] = color;
    if (intensity_) intensity_of_[s] = intensity;
  }

  std::size_t size() const { return size_; }

  /// Which of 2^bits tables owns `key` (CellTables): the hash's top bits, while a table's slots use its low ones.
  static std::size_t part_of(const Key& key, int bits) { return static_cast<std::size_t>(hash(key) >> (64 - bits)); }

  /// The representatives in file order: positions, and normals / colours / intensity when the table keeps them; returns
  /// their file indices (ascending), for the formats that read more of the kept points back from their records.
  std::vector<std::uint64_t> take(std::vector<Vec3f>& positions, std::vector<Vec3f>& normals, std::vector<Rgb8>& colors,
                                  std::vector<float>* intensity = nullptr) const {
    // (file index, slot) pairs sort without chasing the table.
    std::vector<std::pair<std::uint64_t, std::uint32_t>> order;
    order.reserve(size_);
    for (std::size_t s = 0; s < capacity_; ++s)
      if (entries_[s].index != kEmpty) order.emplace_back(entries_[s].index, static_cast<std::uint32_t>(s));
    std::sort(order.begin(), order.end());
    std::vector<std::uint32_t> used(order.size());
    std::vector<std::uint64_t> indices(order.size());
    for (std::size_t i = 0; i < order.size(); ++i) std::tie(indices[i], used[i]) = order[i];
    order = {};
    positions.reserve(used.size());
    for (const std::uint32_t s : used)
      positions.emplace_back(entries_[s].position[0], entries_[s].position[1], entries_[s].position[2]);
    if (normals_)
      for (const std::uint32_t s : used) normals.push_back(normals_of_[s]);
    if (colors_)
      for (const std::uint32_t s : used) colors.push_back(colors_of_[s]);
    if (intensity_ && intensity != nullptr)
      for (const std::uint32_t s : used) intensity->push_back(intensity_of_[s]);
    return indices;
  }

 private:
  static constexpr std::uint64_t kEmpty = std::numeric_limits<std::uint64_t>::max();
  struct Entry {
    Key key{};
    std::array<float, 3> position{};
    double distance2 = 0;
    std::uint64_t index = kEmpty;
  };
  static_assert(sizeof(Entry) == 40, "a slot is 40 bytes: docs/io.md");

  static std::uint64_t hash(const Key& k) {
    std::uint64_t h = static_cast<std::uint32_t>(k[0]) * 0x9e3779b97f4a7c15ull;
    h ^= static_cast<std::uint32_t>(k[1]) * 0xc2b2ae3d27d4eb4full + (h >> 29);
    h ^= static_cast<std::uint32_t>(k[2]) * 0x165667b19e3779f9ull + (h >> 31);
    h *= 0xbf58476d1ce4e5b9ull;
    return h ^ (h >> 32);
  }

  // The slot holding `key`, or the empty slot where it goes.
  std::size_t slot(const Key& key) const {
    const std::size_t mask = capacity_ - 1;
    std::size_t s = static_cast<std::size_t>(hash(key)) & mask;
    while (entries_[s].index != kEmpty && entries_[s].key != key) s = (s + 1) & mask;
    return s;
  }

  void resize(std::size_t capacity) {
    const std::vector<Entry> old = std::move(entries_);
    const std::size_t old_capacity = capacity_;
    std::vector<Vec3f> old_normals = std::move(normals_of_);
    std::vector<Rgb8> old_colors = std::move(colors_of_);
    std::vector<float> old_intensity = std::move(intensity_of_);
    entries_.assign(capacity, Entry{});
    capacity_ = capacity;
    if (normals_) normals_of_.assign(capacity, Vec3f::Zero());
    if (colors_) colors_of_.assign(capacity, Rgb8{});
    if (intensity_) intensity_of_.assign(capacity, 0.f);
    for (std::size_t i = 0; i < old_capacity; ++i) {
      if (old[i].index == kEmpty) continue;
      const std::size_t s = slot(old[i].key);
      entries_[s] = old[i];
      if (normals_) normals_of_[s] = old_normals[i];
      if (colors_) colors_of_[s] = old_colors[i];
      if (intensity_) intensity_of_[s] = old_intensity[i];
    }
  }

  bool normals_, colors_, intensity_;
  std::vector<Entry> entries_;
  std::size_t capacity_ = 0;  ///< a power of two
  std::vector<Vec3f> normals_of_;
  std::vector<Rgb8> colors_of_;
  std::vector<float> intensity_of_;
  std::size_t size_ = 0;
};

/// CellTables side by side, each owning the cells whose hash has its top bits, so that the offers of a batch go to
/// them in parallel. The cells kept are one table's: a cell's representative is the least of its offers under one
/// total order (distance, position, unique file index), whatever order they come in.
class CellTables {
 public:
  static constexpr int kPartBits = 3;
  static constexpr std::size_t kParts = std::size_t{1} << kPartBits;

  CellTables(bool normals, bool colors, bool intensity) {
    for (std::size_t p = 0; p < kParts; ++p) parts_.emplace_back(normals, colors, intensity);
  }

  CellTable& part(std::size_t p) { return parts_[p]; }
  static std::size_t part_of(const CellTable::Key& key) { return CellTable::part_of(key, kPartBits); }

  /// As CellTable::take, over all the tables: each takes its own in parallel, then they are merged by file index.
  std::vector<std::uint64_t> take(std::vector<Vec3f>& positions, std::vector<Vec3f>& normals, std::vector<Rgb8>& colors,
                                  std::vector<float>* intensity = nullptr) const {
    struct Taken {
      std::vector<Vec3f> positions, normals;
      std::vector<Rgb8> colors;
      std::vector<float> intensity;
      std::vector<std::uint64_t> indices;
    };
    std::vector<Taken> taken(kParts);
    tbb::parallel_for(std::size_t{0}, kParts, [&](std::size_t p) {
      Taken& t = taken[p];
      t.indices = parts_[p].take(t.positions, t.normals, t.colors, &t.intensity);
    });
    std::vector<std::uint64_t> indices;
    std::array<std::size_t, kParts> at{};
    for (;;) {
      std::size_t best = kParts;
      for (std::size_t p = 0; p < kParts; ++p)
        if (at[p] < taken[p].indices.size() &&
            (best == kParts || taken[p].indices[at[p]] < taken[best].indices[at[best]]))
          best = p;
      if (best == kParts) return indices;
      const Taken& t = taken[best];
      const std::size_t i = at[best]++;
      indices.push_back(t.indices[i]);
      positions.push_back(t.positions[i]);
      if (!t.normals.empty()) normals.push_back(t.normals[i]);
      if (!t.colors.empty()) colors.push_back(t.colors[i]);
      if (intensity != nullptr && !t.intensity.empty()) intensity->push_back(t.intensity[i]);
    }
  }

 private:
  std::vector<CellTable> parts_;
};

}  // namespace pcsketch::io::detail
