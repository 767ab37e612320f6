// The memory estimate of a drawing (validate.h): the image buffers plus a measured cost per point and neighbour,
// checked before the analysis against DrawOptions::max_memory_gb (--max-memory) or the machine's memory.

#include <gtest/gtest.h>

#include <string>

#include "pcsketch/pipeline.h"
#include "pcsketch/validate.h"
#include "support/analytic_shapes.h"

namespace pcsketch {
namespace {

DrawOptions small_image() {
  DrawOptions o;
  o.camera.width = o.camera.height = 96;
  return o;
}

TEST(ValidateMemory, EstimateIsTheImageBuffersPlusThePointsAndTheirNeighbours) {
  DrawOptions o = small_image();
  // A8 raster 96 x 96 bytes; attached-shadow grid of 2 px cells, 48 x 48 cells of 21 bytes.
  EXPECT_DOUBLE_EQ(image_bytes(o, o.camera), 9216 + 48384);
  EXPECT_DOUBLE_EQ(point_bytes(o.surface, 1000), 1000 * (256 + 28 * 16));
  o.surface.neighbourhood.k = 64;
  EXPECT_DOUBLE_EQ(point_bytes(o.surface, 1000), 1000 * (256 + 28 * 64));
  EXPECT_GT(physical_memory_bytes(), 1e8);
}

TEST(ValidateMemory, PrepareRefusesACloudOverTheLimitAndAcceptsItAtTheLimit) {
  const PointCloud cloud = test::sphere(1.f, {.n = 300});
  DrawOptions o = small_image();
  const double bytes = 9216 + 48384 + 300 * 704;  // 268800
  o.max_memory_gb = (bytes + 1) / 1e9;
  EXPECT_TRUE(prepare(cloud, o).analysed());
  o.max_memory_gb = (bytes - 1) / 1e9;
  try {
    (void)prepare(cloud, o);
    ADD_FAILURE() << "accepted";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.flag(), "--max-memory");
    EXPECT_EQ(std::string(e.what()).find("--max-memory: the cloud: 300 points (--neighbours 16) and a 96x96 image need "
                                         "about 0.000269 GB, over the limit of 0.000269 GB"),
              0u)
        << e.what();
  }
}

TEST(ValidateMemory, ATinyCloudWithAHugeImageIsRefused) {
  DrawOptions o;
  o.camera.width = o.camera.height = 20000;
  o.shadow.mode = stylize::ShadowMode::None;  // 0.4 GB of raster: within the 2 GiB image limit
  EXPECT_NO_THROW(validate(o));
  o.max_memory_gb = 0.3;
  EXPECT_THROW(validate_memory(o, 5, "five.xyz"), OptionError);
  o.max_memory_gb = 0.5;
  EXPECT_NO_THROW(validate_memory(o, 5, "five.xyz"));
}

}  // namespace
}  // namespace pcsketch
