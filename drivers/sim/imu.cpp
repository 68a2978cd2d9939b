#include "drivers/sim/imu.hpp"

#include "drivers/sim/sampling.hpp"

#include <algorithm>
#include <cmath>

namespace stairs::sim {

namespace {
constexpr double kGravity_mps2 = 9.80665;  // standard gravity
constexpr double kDifference_s = 0.002;    // s; step of the finite differences of the trajectory
}  // namespace

ImuSim::ImuSim(const Trajectory& trajectory, const ImuNoise& noise, uint64_t seed)
    : trajectory_(trajectory), noise_(noise), rng_(seed ^ 0x696d7573616d706cULL) {
  for (int i = 0; i < 3; ++i) {
    accel_bias_[i] = noise_.accel_bias_mps2 * (2.0 * rng_.uniform() - 1.0);
    gyro_bias_[i] = noise_.gyro_bias_radps * (2.0 * rng_.uniform() - 1.0);
  }
}

ImuSample ImuSim::measure(double t) {
  // Over one sample interval, as a real IMU integrates it: the rotation since
  // the last sample (so that integrating the rates gives back the trajectory's
  // attitude, kinks included), and the acceleration by a central difference.
  const double h = 1.0 / noise_.rate_hz;
  // The walk starts at t = 0: no differences reach before it (one-sided there).
  const double m = std::max(t, h);
  const Eigen::Isometry3d a = trajectory_.pose_at(m - h), b = trajectory_.pose_at(m), c = trajectory_.pose_at(m + h);
  // Motion acceleration (stair frame), then the specific force the
  // accelerometer feels: acceleration minus gravity, in the optical frame.
  const Eigen::Vector3d accel = (c.translation() - 2.0 * b.translation() + a.translation()) / (h * h);
  const Eigen::Vector3d force = b.linear().transpose() * (accel + Eigen::Vector3d(0, 0, kGravity_mps2));
  const Eigen::AngleAxisd turn(trajectory_.pose_at(t - h).linear().transpose() * trajectory_.pose_at(t).linear());
  const Eigen::Vector3d rate = t < h ? Eigen::Vector3d::Zero() : Eigen::Vector3d(turn.axis() * turn.angle() / h);
  ImuSample s;
  s.specific_force_mps2 = force + accel_bias_ +
                          noise_.accel_noise_mps2 * Eigen::Vector3d(rng_.gaussian(), rng_.gaussian(), rng_.gaussian());
  s.angular_rate_radps = rate + gyro_bias_ +
                         noise_.gyro_noise_radps * Eigen::Vector3d(rng_.gaussian(), rng_.gaussian(), rng_.gaussian());
  return s;
}

std::vector<ImuSample> ImuSim::until(double t_s, int64_t utime0) {
  return samples_until(next_, noise_.rate_hz, t_s, utime0, [this](double t) { return measure(t); });
}

}  // namespace stairs::sim
