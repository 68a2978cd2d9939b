#include "perception/imu_gravity.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace stairs {

namespace {
constexpr double kGravity_mps2 = 9.80665;  // standard gravity
double deg(double rad) { return rad * 180.0 / M_PI; }
}  // namespace

Eigen::Matrix3d imu_to_camera(const ImuConfig& c) {
  const double r = c.to_camera_roll_deg * M_PI / 180.0, p = c.to_camera_pitch_deg * M_PI / 180.0,
               y = c.to_camera_yaw_deg * M_PI / 180.0;
  return (Eigen::AngleAxisd(y, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(p, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(r, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

ImuSample turned(const ImuSample& s, const Eigen::Matrix3d& imu_to_camera) {
  ImuSample out = s;
  out.specific_force_mps2 = imu_to_camera * s.specific_force_mps2;
  out.angular_rate_radps = imu_to_camera * s.angular_rate_radps;
  return out;
}

void ImuGravity::add(const ImuSample& s) {
  if (started_ && s.utime <= last_utime_) {
    if ((last_utime_ - s.utime) * 1e-6 <= c_.max_age_s) {
      ++dropped_;
      return;
    }
    started_ = false;  // far back: a new stream (a log replayed) starts the filter again
  }
  const Eigen::Vector3d& f = s.specific_force_mps2;
  const double dt = started_ ? (s.utime - last_utime_) * 1e-6 : 0.0;
  if (!started_ || dt > c_.max_age_s) {
    if (std::abs(f.norm() - kGravity_mps2) > c_.max_force_deviation * kGravity_mps2) return;  // no start from a jolt
    gravity_ = f;
    started_ = true;
    first_utime_ = last_utime_ = s.utime;
    return;
  }
  // A world-fixed vector seen from a frame turning at w turns by -w dt.
  const double turn = s.angular_rate_radps.norm() * dt;
  if (turn > 0) gravity_ = Eigen::AngleAxisd(-turn, s.angular_rate_radps.normalized()) * gravity_;
  // The specific force itself is low-passed, not its direction: a walking
  // carrier's bounce and surge average out to zero only as vectors.
  if ((f - gravity_).norm() <= c_.max_force_deviation * kGravity_mps2 * 2.0)
    gravity_ += std::min(1.0, dt / c_.time_constant_s) * (f - gravity_);
  last_utime_ = s.utime;
}

std::optional<Eigen::Vector3f> ImuGravity::up_at(int64_t utime) const {
  if (!started_ || (last_utime_ - first_utime_) * 1e-6 < c_.warmup_s) return std::nullopt;
  if (std::abs(utime - last_utime_) * 1e-6 > c_.max_age_s) return std::nullopt;
  return gravity_.normalized().cast<float>();
}

FusedUp fuse_up(const std::optional<Eigen::Vector3f>& planes, const std::optional<Eigen::Vector3f>& imu,
                const ImuConfig& c) {
  if (!imu) return {planes, ""};
  char note[96];
  if (!planes) return {imu, "gravity from the IMU (no horizontal plane)"};
  const double off = deg(std::acos(std::clamp(static_cast<double>(planes->dot(*imu)), -1.0, 1.0)));
  if (off <= c.plane_agreement_deg) return {planes, ""};
  if (off <= c.max_disagreement_deg) {
    std::snprintf(note, sizeof note, "gravity from the IMU (the planes are %.1f deg off: a slope)", off);
    return {imu, note};
  }
  std::snprintf(note, sizeof note, "IMU rejected: %.1f deg from the planes", off);
  return {planes, note};
}

}  // namespace stairs
