// The hand-written neighbour search against nanoflann on the same queries (the README's reason for it): the 16
// nearest of every point of spatially ordered clouds, as the pipeline asks them.
//
//   bench_knn [N]   sample count of each cloud (default 1000000)
//
// Rows: nanoflann's serial build; nanoflann's 16-NN of every point (parallel, one query a point); the grid's rows plus
// the tree's for the rest, given a built tree; and the pipeline's step, the grid's search with the tree built only if
// rows are left (the tree builds itself at its first query).
// Both searches give the same lists bit for bit (tests/neighbourhood/grid_knn_test.cpp); this checks it again.

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <iostream>
#include <random>

#include "pcsketch/neighbourhood/neighbourhoods.h"
#include "pcsketch/neighbourhood/spatial_order.h"
#include "support/bench_support.h"

namespace pcsketch::bench {
namespace {

struct Measured {
  std::size_t points = 0;
  double build = 0, tree_knn = 0, grid_knn = 0, together = 0;
  bool equal = false;
};

/// Gaussian noise of σ = `sigma` × the bounding-box diagonal, then `outliers` × n uniform points in the box.
void spoil(PointCloud& cloud, double sigma, double outliers) {
  const Box3f box = bounding_box(cloud.positions);
  std::mt19937_64 rng(7);
  std::normal_distribution<float> noise(0.f, static_cast<float>(sigma * box.diagonal()));
  for (Vec3f& p : cloud.positions) p += Vec3f(noise(rng), noise(rng), noise(rng));
  std::uniform_real_distribution<float> u(0.f, 1.f);
  const auto extra = static_cast<std::size_t>(outliers * static_cast<double>(cloud.size()));
  for (std::size_t i = 0; i < extra; ++i)
    cloud.positions.push_back(box.min + Vec3f(u(rng), u(rng), u(rng)).cwiseProduct(box.size()));
}

Measured measure(const std::string& mesh, std::size_t n, double sigma, double outliers) {
  PointCloud cloud = sampled_cloud(shared_data(mesh), n, 2024);
  spoil(cloud, sigma, outliers);
  neighbourhood::reorder_spatially(cloud);
  const std::vector<Vec3f>& points = cloud.positions;
  Measured m;
  m.points = points.size();
  Stopwatch clock;
  const neighbourhood::KdTree tree(points);
  std::vector<std::uint32_t> first;
  std::vector<float> first_distance;
  tree.knn(points[0], 1, first, first_distance);  // the build
  m.build = clock.seconds();
  std::vector<std::uint32_t> tree_rows(points.size() * 16);
  clock.restart();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 256), [&](const auto& r) {
    std::vector<std::uint32_t> found;
    std::vector<float> distances;
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      tree.knn_of_point(i, 16, found, distances);
      std::copy(found.begin(), found.end(), tree_rows.begin() + static_cast<std::ptrdiff_t>(i * 16));
    }
  });
  m.tree_knn = clock.seconds();
  clock.restart();
  const neighbourhood::Neighbourhoods grid = neighbourhood::compute_neighbourhoods(tree, points, {.k = 16});
  m.grid_knn = clock.seconds();
  clock.restart();
  std::optional<neighbourhood::KdTree> built;
  const neighbourhood::Neighbourhoods both = neighbourhood::index_neighbourhoods(points, built, {.k = 16});
  m.together = clock.seconds();
  m.equal = std::ranges::equal(grid.indices, tree_rows) && std::ranges::equal(both.indices, tree_rows);
  return m;
}

int run(int argc, char** argv) {
  const std::size_t n = argc > 1 ? std::stoul(argv[1]) : 1000000;
  std::cout << "load average before: " << load_average() << "\n";
  const std::vector<std::string> names{"bunny clean", "bunny σ 0.1%", "camel σ 0.2% + 1% outliers"};
  const std::vector<Measured> results{measure("bunny.off", n, 0, 0), measure("bunny.off", n, 0.001, 0),
                                      measure("camel.off", n, 0.002, 0.01)};
  Table table = per_point_table("16-NN of every point", names);
  const auto row = [&](const std::string& label, auto seconds_of) {
    add_per_point_row(table, label, results, seconds_of);
  };
  row("kd-tree build (nanoflann, serial)", [](const Measured& m) { return m.build; });
  row("k-NN, nanoflann (a query a point)", [](const Measured& m) { return m.tree_knn; });
  row("k-NN, grid + tree for the rest", [](const Measured& m) { return m.grid_knn; });
  row("build + nanoflann k-NN (before)", [](const Measured& m) { return m.build + m.tree_knn; });
  row("grid k-NN, tree only if rows are left (now)", [](const Measured& m) { return m.together; });
  std::vector<std::string> equal{"same lists"}, points{"points"};
  for (const Measured& m : results) {
    equal.insert(equal.end(), {m.equal ? "yes" : "NO", ""});
    points.insert(points.end(), {grouped(m.points), ""});
  }
  table.add_row(equal);
  table.add_row(points);
  std::cout << table.to_string() << "load average after: " << load_average() << "\n";
  return 0;
}

}  // namespace
}  // namespace pcsketch::bench

int main(int argc, char** argv) { return pcsketch::bench::bench_main("bench_knn", argc, argv, pcsketch::bench::run); }
