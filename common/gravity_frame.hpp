// The gravity-aligned camera frame (DESIGN.md 'Frames and units') of a camera
// posed in a z-up frame (the stair frame, the tracker's model frame).
#pragma once

#include <Eigen/Geometry>

namespace stairs {

// Origin at the camera centre, x = the horizontal projection of the optical
// axis (looking straight down: of the image's up direction), z up, y = z x x.
// `optical_to_frame` rotates optical-frame vectors (x right, y down, z forward)
// into the z-up frame.
inline Eigen::Isometry3d gravity_frame_pose(const Eigen::Vector3d& position_m,
                                            const Eigen::Quaterniond& optical_to_frame) {
  const Eigen::Matrix3d R = optical_to_frame.normalized().toRotationMatrix();
  Eigen::Vector3d forward = R.col(2);
  forward.z() = 0.0;
  if (forward.norm() < 1e-6) {
    forward = -R.col(1);
    forward.z() = 0.0;
  }
  forward.normalize();
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear().col(0) = forward;
  T.linear().col(1) = up.cross(forward);
  T.linear().col(2) = up;
  T.translation() = position_m;
  return T;
}

}  // namespace stairs
