#include "perception/gravity.hpp"
#include "perception/normals.hpp"
#include "perception/region_growing.hpp"
#include "synthetic.hpp"

#include <gtest/gtest.h>

namespace stairs {
namespace {

TEST(PerceptionNormals, FloorNormalsPointUpTowardsTheCamera) {
  const DepthImage img = test::render_stairs(320, 240, -40, 5, 1.0, 0);
  NormalGrid g;
  compute_normals(img, PerceptionConfig{}, g);
  EXPECT_EQ(g.width, 160);
  EXPECT_EQ(g.height, 120);
  // Floor normal (world up) in optical coordinates.
  const Eigen::Vector3f up = (test::optical_to_world(-40, 5).transpose() * Eigen::Vector3d::UnitZ()).cast<float>();
  int n = 0, close = 0;
  for (size_t i = 0; i < g.normals.size(); ++i) {
    if (!g.has_normal[i]) continue;
    ++n;
    if (g.normals[i].dot(up) > std::cos(2.0 * M_PI / 180)) ++close;
  }
  EXPECT_GT(n, 10000);
  EXPECT_GT(close, 0.98 * n);
}

TEST(PerceptionNormals, EmptyAndTinyFramesGiveNoNormals) {
  PerceptionConfig cfg;
  NormalGrid g;
  DepthImage img;
  img.K = {3, 2, 1, 1, 1, 1};
  img.depth.assign(6, 1000);
  compute_normals(img, cfg, g);
  for (uint8_t h : g.has_normal) EXPECT_EQ(h, 0);
}

TEST(PerceptionRegionGrowing, StairsAreSegmentedIntoTreadsAndRisers) {
  const DepthImage img = test::render_stairs(640, 480, -35, 0, 1.0, 3, 1.2);
  PerceptionConfig cfg;
  NormalGrid g;
  compute_normals(img, cfg, g);
  std::vector<int> labels;
  const auto segs = grow_regions(g, cfg, 640, 480, labels);
  // Floor, 3 treads, 3 risers; over-segmentation is allowed, mixing is not.
  ASSERT_GE(segs.size(), 7u);
  for (const Segment& s : segs) EXPECT_LT(s.rms_m, 0.01f);
  // The top level is in view: floor + 3 treads + 3 risers at least.
}

TEST(PerceptionRegionGrowing, SmallPlanesAreDroppedWithTheScaledThreshold) {
  PerceptionConfig cfg;
  cfg.min_plane_px_320 = 1000000;  // larger than any frame
  const DepthImage img = test::render_stairs(320, 240, -35, 0, 1.0, 0);
  NormalGrid g;
  compute_normals(img, cfg, g);
  std::vector<int> labels;
  EXPECT_TRUE(grow_regions(g, cfg, 320, 240, labels).empty());
  for (int l : labels) EXPECT_EQ(l, -1);
}

TEST(PerceptionGravity, PoseConventionsRoundTrip) {
  for (double pitch : {-75.0, -35.0, -5.0, 10.0})
    for (double roll : {-10.0, 0.0, 4.0}) {
      const Eigen::Matrix3d R = test::optical_to_world(pitch, roll);
      const Eigen::Vector3f up = (R.transpose() * Eigen::Vector3d::UnitZ()).cast<float>();
      const CameraPose p = pose_from_up(up);
      EXPECT_NEAR(p.pitch_deg, pitch, 1e-3);
      EXPECT_NEAR(p.roll_deg, roll, 1e-3);
      // gravity_rotation maps optical into x forward, y left, z up: the
      // same as the world frame up to yaw (zero here).
      const Eigen::Matrix3d G = p.gravity_rotation.toRotationMatrix();
      EXPECT_TRUE(G.isApprox(R, 1e-5)) << "pitch " << pitch << " roll " << roll;
    }
}

TEST(PerceptionGravity, PitchAndRollFromTheFloorAndSteps) {
  const DepthImage img = test::render_stairs(640, 480, -30, 3, 1.1, 3, 1.5);
  PerceptionConfig cfg;
  NormalGrid g;
  compute_normals(img, cfg, g);
  std::vector<int> labels;
  const auto segs = grow_regions(g, cfg, 640, 480, labels);
  const auto up = estimate_up(segs, cfg);
  ASSERT_TRUE(up.has_value());
  const CameraPose p = pose_from_up(*up);
  EXPECT_NEAR(p.pitch_deg, -30, 0.3);
  EXPECT_NEAR(p.roll_deg, 3, 0.3);
}

TEST(PerceptionGravity, NoHorizontalPlaneNoPose) {
  // A wall straight ahead: its normal is 90 deg from image up.
  Segment wall;
  wall.normal = {0, 0, -1};
  wall.cells.assign(5000, 0);
  EXPECT_FALSE(estimate_up({wall}, PerceptionConfig{}).has_value());
}

}  // namespace
}  // namespace stairs
