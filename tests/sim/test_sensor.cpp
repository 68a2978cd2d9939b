// The Kinect v1 sensor model: determinism, axial noise, shadow, ranges.
#include "drivers/sim/render.hpp"
#include "drivers/sim/trajectory.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace stairs;
using namespace stairs::sim;

namespace {
Intrinsics kinect() { return {640, 480, 525.0, 525.0, 319.5, 239.5}; }

// An empty room whose far wall is `distance_m` ahead of the camera.
Scene wall_scene() {
  Scene s = make_preset("flat_room");
  s.boxes.clear();
  s.flat_length_m = 4.0;
  return s;
}
}  // namespace

TEST(SimSensor, SameSeedSameBytes) {
  const Scene s = make_preset("cluttered");
  const Trajectory traj(s, trajectory_defaults(Carrier::HandHeld));
  Renderer a(s, kinect(), SensorModel{}, 42), b(s, kinect(), SensorModel{}, 42), c(s, kinect(), SensorModel{}, 43);
  for (int f : {0, 30, 60}) {
    const DepthImage ia = a.render(traj.pose(f), 1000 + f, f);
    EXPECT_EQ(ia.depth, b.render(traj.pose(f), 1000 + f, f).depth);
    EXPECT_NE(ia.depth, c.render(traj.pose(f), 1000 + f, f).depth);
  }
  // A frame's noise depends on (seed, seq), not on the frames rendered before.
  Renderer d(s, kinect(), SensorModel{}, 42);
  EXPECT_EQ(d.render(traj.pose(60), 0, 60).depth, a.render(traj.pose(60), 0, 60).depth);
}

// sigma(z) = 0.0012 + 0.0019 (z - 0.4)^2 on a flat wall, with quantisation
// (and the 1 mm output unit) on, measured against the formula.
TEST(SimSensor, AxialNoiseMatchesNguyenModel) {
  const Scene s = wall_scene();
  SensorModel m;
  m.holes = false;  // holes only remove pixels; they are excluded anyway
  for (double z : {1.0, 2.0, 3.0}) {
    Renderer r(s, kinect(), m, 7);
    const Eigen::Isometry3d T = camera_pose({4.0 - z, 0.0, 1.3}, 0.0, 0.0, 0.0);
    double sum = 0.0, sum2 = 0.0;
    long n = 0;
    for (int f = 0; f < 4; ++f) {
      const DepthImage img = r.render(T, 0, f);
      for (int v = 140; v < 340; ++v)
        for (int u = 220; u < 420; ++u) {
          const uint16_t d = img.depth[static_cast<size_t>(v) * 640 + u];
          if (d == 0) continue;
          const double e = d * 0.001 - z;
          sum += e, sum2 += e * e, ++n;
        }
    }
    ASSERT_GT(n, 100000);
    const double mean = sum / n, sigma = std::sqrt(sum2 / n - mean * mean);
    const double expected = 0.0012 + 0.0019 * (z - 0.4) * (z - 0.4);
    EXPECT_NEAR(sigma, expected, 0.2 * expected) << "z = " << z;
    EXPECT_NEAR(mean, 0.0, 0.25 * expected) << "z = " << z;
    std::printf("sigma(%.0f m): measured %.5f m, formula %.5f m (%+.1f%%), bias %+.5f m\n", z, sigma, expected,
                100.0 * (sigma / expected - 1.0), mean);
  }
}

TEST(SimSensor, RangeLimits) {
  const Scene s = wall_scene();
  Renderer r(s, kinect(), perfect_sensor(), 1);
  auto centre = [&](double z) {
    return r.render(camera_pose({4.0 - z, 0.0, 1.3}, 0.0, 0.0, 0.0), 0, 0).depth[240 * 640 + 320];
  };
  EXPECT_EQ(centre(0.45), 0);
  EXPECT_EQ(centre(0.6), 600);
  EXPECT_EQ(centre(4.4), 4400);
  EXPECT_EQ(centre(4.6), 0);
}

// The projector, 7.5 cm to the camera's right, casts a shadow on the far
// surface beside the left edge of a nearer object.
TEST(SimSensor, ProjectorShadowBesideLeftEdgeOfNearObject) {
  Scene s = wall_scene();
  s.boxes.push_back({{2.0, -0.2, 0.0}, {2.2, 0.2, 2.0}});  // a pillar 1.5 m ahead, 2 m before the wall
  SensorModel only_shadow = perfect_sensor();
  only_shadow.perfect = false;
  only_shadow.axial_noise = only_shadow.quantisation = only_shadow.lateral_noise = false;
  only_shadow.grazing_dropout = only_shadow.holes = false;
  const Eigen::Isometry3d T = camera_pose({0.5, 0.0, 1.3}, 0.0, 0.0, 0.0);
  const DepthImage clean = Renderer(s, kinect(), perfect_sensor(), 1).render(T, 0, 0);
  const DepthImage shadowed = Renderer(s, kinect(), only_shadow, 1).render(T, 0, 0);
  const int v = 240;
  auto at = [&](const DepthImage& img, int u) { return img.depth[static_cast<size_t>(v) * 640 + u]; };
  // Pillar left edge (y = +0.2) at u = 319.5 - 525 * 0.2 / 1.5 = 249.5.
  EXPECT_EQ(at(clean, 250), 1500);
  EXPECT_EQ(at(clean, 249), 3500);
  // Shadow on the wall: from the edge leftwards by f * b * (1/1.5 - 1/3.5) = 15 px.
  int shadow_px = 0;
  for (int u = 200; u < 250; ++u) shadow_px += at(shadowed, u) == 0;
  EXPECT_NEAR(shadow_px, 15, 1);
  for (int u = 251; u < 330; ++u) EXPECT_EQ(at(shadowed, u), 1500);  // nothing on the pillar itself
  for (int u = 390; u < 640; ++u) EXPECT_NE(at(shadowed, u), 0);     // nor right of it
}

// A dark tread reads nothing on dark_dropout of its pixels on every sensor model: a pixel without a
// return is no depth edge, so a stereo camera's edge holes must not spread the dropout (they did:
// 74 % of a D435's dark tread read nothing for 50 %).
TEST(SimSensor, DarkTreadsDropTheirShareOfPixelsOnEverySensor) {
  Scene s = make_preset("dark_treads");
  s.flights = {uniform_flight(2, 0.18, 1.5, 3.0)};  // a 1.5 m deep first tread fills the view
  const Eigen::Isometry3d T = camera_pose({0.75, 0.0, 0.18 + 0.8}, 0.0, -90.0, 0.0);
  for (const char* name : {"kinect1", "kinect2", "d435"}) {
    SensorModel m = sensor_preset(name);
    m.holes = false;  // the sensor's own random holes are not the dark surface's
    const Intrinsics K = sensor_intrinsics(m.kind, 0, 0);
    const DepthImage img = Renderer(s, K, m, 3).render(T, 0, 0);
    long zeros = 0, n = 0;
    for (int v = K.height / 4; v < 3 * K.height / 4; ++v)
      for (int u = K.width / 4; u < 3 * K.width / 4; ++u, ++n) zeros += img.depth[static_cast<size_t>(v) * K.width + u] == 0;
    EXPECT_NEAR(static_cast<double>(zeros) / n, m.dark_dropout, 0.02) << name;
  }
}

// The depth warp: off by default (every other test's bytes as they were), and when asked for, a flat
// wall seen face-on reads depth x (1 + warp (rho^2 - 1/2)): deeper in the corners, shallower at the
// centre, by the fraction given.
TEST(SimSensor, DepthWarpBendsAFlatWallByTheFractionGiven) {
  const Scene s = wall_scene();
  const Eigen::Isometry3d T = camera_pose({2.0, 0.0, 1.3}, 0.0, 0.0, 0.0);  // the wall 2 m ahead
  SensorModel m;
  m.shadow = m.axial_noise = m.quantisation = m.lateral_noise = m.grazing_dropout = m.holes = false;
  EXPECT_EQ(m.depth_warp, 0.0);
  Renderer flat(s, kinect(), m, 3);
  m.depth_warp = 0.02;
  Renderer warped(s, kinect(), m, 3);
  const DepthImage a = flat.render(T, 0, 0), b = warped.render(T, 0, 0);
  const auto at = [](const DepthImage& img, int u, int v) { return img.depth[static_cast<size_t>(v) * 640 + u]; };
  EXPECT_EQ(at(a, 320, 240), 2000);
  EXPECT_EQ(at(a, 5, 5), 2000);
  EXPECT_NEAR(at(b, 320, 240), 2000 * (1 - 0.01), 1);  // rho = 0
  const double rho2 = ((5 - 319.5) * (5 - 319.5) + (5 - 239.5) * (5 - 239.5)) / (0.25 * (640.0 * 640 + 480.0 * 480));
  EXPECT_NEAR(at(b, 5, 5), 2000 * (1 + 0.02 * (rho2 - 0.5)), 1);
}
