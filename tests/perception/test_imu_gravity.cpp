// Gravity from an optional IMU (perception/imu_gravity.hpp).
#include "perception/imu_gravity.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace stairs {
namespace {

constexpr double kG = 9.80665;

double angle_deg(const Eigen::Vector3f& a, const Eigen::Vector3d& b) {
  return std::acos(std::clamp(a.cast<double>().normalized().dot(b.normalized()), -1.0, 1.0)) * 180.0 / M_PI;
}

ImuSample at_rest(int64_t utime, const Eigen::Vector3d& up, const Eigen::Vector3d& rate = Eigen::Vector3d::Zero()) {
  ImuSample s;
  s.utime = utime;
  s.specific_force_mps2 = kG * up.normalized();
  s.angular_rate_radps = rate;
  return s;
}

TEST(ImuGravity, UpFromTheAccelerometerAfterTheWarmup) {
  const ImuConfig c;
  ImuGravity f(c);
  const Eigen::Vector3d up(0.1, -0.8, -0.55);  // camera pitched down, rolled a little
  EXPECT_FALSE(f.up_at(0));
  for (int i = 0; i <= 200; ++i) f.add(at_rest(i * 5000, up));  // 1 s at 200 Hz
  ASSERT_TRUE(f.up_at(1000000));
  EXPECT_LT(angle_deg(*f.up_at(1000000), up), 0.01);
  EXPECT_FALSE(f.up_at(1000000 + 200000)) << "stale after max_age_s";
  f.add(at_rest(950000, up));
  EXPECT_EQ(f.dropped(), 1) << "a sample back in time is dropped and counted";
  f.add(at_rest(-5000000, up));
  EXPECT_EQ(f.dropped(), 1) << "5 s back: a new stream (a log replayed), the filter starts again";
  EXPECT_FALSE(f.up_at(-5000000)) << "warming up again";
}

// The camera turns 30 deg about its optical axis in 0.5 s: the gyroscope
// carries the up along at once, which the accelerometer alone (time constant
// 1 s) would follow only slowly.
TEST(ImuGravity, GyroscopeCarriesTheUpThroughATurn) {
  ImuGravity f{ImuConfig{}};
  const Eigen::Vector3d up0(0, -1, 0);
  int64_t t = 0;
  for (int i = 0; i < 200; ++i, t += 5000) f.add(at_rest(t, up0));
  const double rate = (30.0 * M_PI / 180.0) / 0.5;  // rad/s about the optical axis (z)
  Eigen::Vector3d up = up0;
  for (int i = 0; i < 100; ++i, t += 5000) {
    up = Eigen::AngleAxisd(-rate * 0.005, Eigen::Vector3d::UnitZ()) * up;  // the world turns the other way
    f.add(at_rest(t, up, Eigen::Vector3d(0, 0, rate)));
  }
  ASSERT_TRUE(f.up_at(t));
  EXPECT_LT(angle_deg(*f.up_at(t), up), 0.5);
}

// A walking carrier's acceleration averages out: half a degree on average
// (issue 15's floor), though single samples swing further. Gait: a 2 m/s^2
// bounce along gravity and 1 m/s^2 fore and aft at the step frequency (2 Hz),
// 0.5 m/s^2 of sway at half of it.
TEST(ImuGravity, WalkingAccelerationAveragesOut) {
  ImuGravity f{ImuConfig{}};
  const Eigen::Vector3d up(0, -0.82, -0.57);
  int64_t t = 0;
  double sum = 0;
  int n = 0;
  for (int i = 0; i < 2000; ++i, t += 5000) {
    ImuSample s = at_rest(t, up);
    const double ts = t * 1e-6;
    const Eigen::Vector3d forward = Eigen::Vector3d::UnitZ() - Eigen::Vector3d::UnitZ().dot(up.normalized()) * up.normalized();
    s.specific_force_mps2 += (2.0 * up.normalized() + 1.0 * forward.normalized()) * std::sin(2 * M_PI * 2.0 * ts) +
                             0.5 * Eigen::Vector3d::UnitX() * std::sin(2 * M_PI * 1.0 * ts);
    f.add(s);
    if (i > 400 && f.up_at(t)) sum += angle_deg(*f.up_at(t), up), ++n;
  }
  ASSERT_GT(n, 1000);
  EXPECT_LT(sum / n, 0.5);
}

TEST(ImuGravity, FusionKeepsAgreeingPlanesUsesTheImuOnASlopeAndRejectsABadOne) {
  const ImuConfig c;  // agreement 2 deg, rejection beyond 10 deg
  const Eigen::Vector3f imu(0, -1, 0);
  const auto turned = [&](double deg) {
    return Eigen::Vector3f((Eigen::AngleAxisf(static_cast<float>(deg * M_PI / 180), Eigen::Vector3f::UnitX()) * imu));
  };
  FusedUp u = fuse_up(turned(1.0), imu, c);
  EXPECT_TRUE(u.up->isApprox(turned(1.0)));
  EXPECT_TRUE(u.note.empty());
  u = fuse_up(turned(5.7), imu, c);
  EXPECT_TRUE(u.up->isApprox(imu));
  EXPECT_NE(u.note.find("slope"), std::string::npos) << u.note;
  u = fuse_up(turned(25.0), imu, c);
  EXPECT_TRUE(u.up->isApprox(turned(25.0)));
  EXPECT_NE(u.note.find("IMU rejected"), std::string::npos) << u.note;
  u = fuse_up(std::nullopt, imu, c);
  EXPECT_TRUE(u.up->isApprox(imu));
  u = fuse_up(turned(3.0), std::nullopt, c);
  EXPECT_TRUE(u.up->isApprox(turned(3.0)));
  EXPECT_TRUE(u.note.empty());
}

TEST(ImuGravity, MountRotationFromTheConfig) {
  ImuConfig c;
  c.to_camera_roll_deg = 90;
  const Eigen::Vector3d v = imu_to_camera(c) * Eigen::Vector3d::UnitY();
  EXPECT_NEAR((v - Eigen::Vector3d::UnitZ()).norm(), 0.0, 1e-12);
}

}  // namespace
}  // namespace stairs
