#include "tracker/odometry_prior.hpp"

#include <cmath>

namespace stairs {

double optical_heading_rad(const Eigen::Quaterniond& q) {
  // Within ~11 deg of vertical (horizontal part < sin 11 deg) the optical axis'
  // heading is ill-defined; the image's up (-y) then points where the camera faces.
  constexpr double kMinHorizontalAxis = 0.2;
  Eigen::Vector3d f = q * Eigen::Vector3d::UnitZ();
  if (std::hypot(f.x(), f.y()) < kMinHorizontalAxis) f = q * -Eigen::Vector3d::UnitY();
  return std::atan2(f.y(), f.x());
}

void OdometryPrior::add(const OdometrySample& o) {
  if (!samples_.empty() && o.utime <= samples_.back().utime) {
    if ((samples_.back().utime - o.utime) * 1e-6 <= jump_back_s_) {
      ++dropped_;
      return;
    }
    samples_.clear();  // a new stream (a log replayed): its odometry starts over
  }
  samples_.push_back(o);
  while (samples_.size() > max_samples_) samples_.pop_front();
}

void OdometryPrior::forget_before(int64_t utime) {
  while (samples_.size() > 1 && samples_[1].utime <= utime) samples_.pop_front();
}

std::optional<OdometrySample> OdometryPrior::at(int64_t utime) const {
  if (samples_.empty() || utime < samples_.front().utime) return std::nullopt;
  const OdometrySample& last = samples_.back();
  if (utime >= last.utime) {
    if ((utime - last.utime) * 1e-6 > max_age_s_) return std::nullopt;
    return last;
  }
  // Binary search for the bracketing pair, then interpolate.
  size_t lo = 0, hi = samples_.size() - 1;
  while (hi - lo > 1) {
    const size_t mid = (lo + hi) / 2;
    (samples_[mid].utime <= utime ? lo : hi) = mid;
  }
  const OdometrySample &a = samples_[lo], &b = samples_[hi];
  const double s = static_cast<double>(utime - a.utime) / static_cast<double>(b.utime - a.utime);
  OdometrySample o;
  o.utime = utime;
  o.position_m = a.position_m + s * (b.position_m - a.position_m);
  o.orientation = a.orientation.slerp(s, b.orientation);
  return o;
}

std::optional<Pose4> OdometryPrior::predict(const Pose4& from, int64_t from_utime, int64_t to_utime) const {
  const auto a = at(from_utime), b = at(to_utime);
  if (!a || !b) return std::nullopt;
  const double heading_a = optical_heading_rad(a->orientation);
  const Eigen::AngleAxisd odometry_to_stair(from.yaw_rad - heading_a, Eigen::Vector3d::UnitZ());
  Pose4 p = from;
  p.t_m += odometry_to_stair * (b->position_m - a->position_m);
  p.yaw_rad = wrap_angle(from.yaw_rad + wrap_angle(optical_heading_rad(b->orientation) - heading_a));
  return p;
}

}  // namespace stairs
