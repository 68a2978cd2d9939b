// A 4-DoF pose (yaw about gravity + translation): after gravity alignment the
// stair's planes are horizontal or vertical, so this is all registration needs.
#pragma once

#include <Eigen/Geometry>

#include <cmath>

namespace stairs {

struct Pose4 {
  double yaw_rad = 0.0;
  Eigen::Vector3d t_m = Eigen::Vector3d::Zero();

  Eigen::Matrix3d rotation() const { return Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix(); }
  Eigen::Isometry3d isometry() const {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = rotation();
    T.translation() = t_m;
    return T;
  }
  // The point `offset_m` from the pose's origin, the offset in its frame (the carrier's base from
  // the camera).
  Eigen::Vector3d point_at(const Eigen::Vector3d& offset_m) const { return t_m + rotation() * offset_m; }
};

// Angle wrapped to (-pi, pi].
inline double wrap_angle(double a) { return std::remainder(a, 2.0 * M_PI); }

}  // namespace stairs
