// The motion prior from odometry (tracker/odometry_prior.hpp).
#include "tracker/odometry_prior.hpp"

#include <gtest/gtest.h>

namespace stairs {
namespace {

// A camera looking horizontally along the odometry frame's heading_rad
// (optical z forward, x right, y down), at p.
OdometrySample sample(int64_t utime, const Eigen::Vector3d& p, double heading_rad) {
  // Optical axes in a z-up frame heading along +x: z_opt = +x, x_opt = -y, y_opt = -z.
  Eigen::Matrix3d level;
  level << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  OdometrySample o;
  o.utime = utime;
  o.position_m = p;
  o.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(heading_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix() * level);
  return o;
}

TEST(OdometryPrior, HeadingOfTheOpticalAxis) {
  EXPECT_NEAR(optical_heading_rad(sample(0, {0, 0, 0}, 0.4).orientation), 0.4, 1e-12);
  EXPECT_NEAR(optical_heading_rad(sample(0, {0, 0, 0}, -2.5).orientation), -2.5, 1e-12);
}

// The odometry frame is turned 90 deg against the stair frame and the camera
// walks 1 m ahead while turning 0.2 rad: in the stair frame it moves 1 m along
// its own heading there, and turns by 0.2 rad.
TEST(OdometryPrior, MotionTurnedIntoTheStairFrame) {
  OdometryPrior prior(0.25, 100, 1.0);
  prior.add(sample(0, {5, 5, 0}, M_PI / 2));
  prior.add(sample(1000000, {5, 6, 0.18}, M_PI / 2 + 0.2));
  Pose4 from;
  from.yaw_rad = 0.3;
  from.t_m = {1, 2, 1};
  const auto p = prior.predict(from, 0, 1000000);
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->t_m.x(), 1 + std::cos(0.3), 1e-9);
  EXPECT_NEAR(p->t_m.y(), 2 + std::sin(0.3), 1e-9);
  EXPECT_NEAR(p->t_m.z(), 1.18, 1e-9);
  EXPECT_NEAR(p->yaw_rad, 0.5, 1e-9);
  // Half way: interpolated.
  const auto half = prior.predict(from, 0, 500000);
  ASSERT_TRUE(half);
  EXPECT_NEAR(half->t_m.z(), 1.09, 1e-9);
}

TEST(OdometryPrior, CoversOnlyWhereSamplesAreFresh) {
  OdometryPrior prior(0.25, 100, 1.0);
  EXPECT_FALSE(prior.covers(0, 100));
  prior.add(sample(1000000, {0, 0, 0}, 0));
  EXPECT_FALSE(prior.covers(0, 1000000)) << "before the first sample";
  EXPECT_TRUE(prior.covers(1000000, 1200000)) << "the last sample holds for max_age_s";
  EXPECT_FALSE(prior.covers(1000000, 1300000));
  prior.add(sample(900000, {0, 0, 0}, 0));
  EXPECT_EQ(prior.dropped(), 1) << "a sample older than the last is dropped and counted";
  prior.add(sample(-5000000, {0, 0, 0}, 0));
  EXPECT_EQ(prior.dropped(), 1) << "5 s back: a new stream, not an out-of-order sample";
  EXPECT_TRUE(prior.covers(-5000000, -4900000));
  EXPECT_FALSE(prior.covers(1000000, 1100000)) << "the old stream is forgotten";
}

TEST(OdometryPrior, HistoryIsCapped) {
  OdometryPrior prior(0.25, 10, 1.0);
  for (int i = 0; i < 50; ++i) prior.add(sample(i * 10000, {0.01 * i, 0, 0}, 0));
  EXPECT_FALSE(prior.covers(0, 490000)) << "the oldest samples are gone";
  EXPECT_TRUE(prior.covers(400000, 490000));
}

}  // namespace
}  // namespace stairs
