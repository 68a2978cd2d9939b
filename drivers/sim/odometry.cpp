#include "drivers/sim/odometry.hpp"

#include "drivers/sim/sampling.hpp"

#include <cmath>

namespace stairs::sim {

namespace {
Eigen::Matrix3d yaw(double rad) { return Eigen::AngleAxisd(rad, Eigen::Vector3d::UnitZ()).toRotationMatrix(); }
}  // namespace

OdometrySim::OdometrySim(const Trajectory& trajectory, const OdometryNoise& noise, uint64_t seed)
    : trajectory_(trajectory), noise_(noise), rng_(seed ^ 0x6f646f6d65747279ULL) {
  scale_ = noise_.scale_error * (2.0 * rng_.uniform() - 1.0);
  yaw_bias_rad_per_s_ = noise_.yaw_bias_deg_per_s * M_PI / 180.0 * (2.0 * rng_.uniform() - 1.0);
  yaw_error_rad_ = 2.0 * M_PI * rng_.uniform();  // the odometry frame's heading vs. the stair's
  origin_m_ = Eigen::Vector3d(10.0 * rng_.uniform() - 5.0, 10.0 * rng_.uniform() - 5.0, rng_.uniform());
  true_ = trajectory_.pose_at(0.0);
  position_m_ = yaw(yaw_error_rad_) * true_.translation() + origin_m_;
}

void OdometrySim::step_to(double t_s) {
  const double dt = t_s - t_;
  if (dt <= 0) return;
  const Eigen::Isometry3d next = trajectory_.pose_at(t_s);
  const Eigen::Vector3d walk(rng_.gaussian(), rng_.gaussian(), rng_.gaussian());
  position_m_ += yaw(yaw_error_rad_) * (next.translation() - true_.translation()) * (1.0 + scale_) +
                 noise_.position_walk_m * std::sqrt(dt) * walk;
  yaw_error_rad_ += yaw_bias_rad_per_s_ * dt + noise_.yaw_walk_deg * M_PI / 180.0 * std::sqrt(dt) * rng_.gaussian();
  true_ = next;
  t_ = t_s;
}

std::vector<OdometrySample> OdometrySim::until(double t_s, int64_t utime0) {
  return samples_until(next_, noise_.rate_hz, t_s, utime0, [this](double t) {
    step_to(t);
    OdometrySample o;
    o.position_m = position_m_;
    o.orientation = Eigen::Quaterniond(yaw(yaw_error_rad_) * true_.linear()).normalized();
    return o;
  });
}

}  // namespace stairs::sim
