// Where the camera sits on its carrier: the config file's top-level "mount"
// object. A property of the robot, not of one stage: perception's camera
// height reads it, and the tracker, which gives the robot's base and predicts
// the base's motion (issue 15, "the mount"); stairs-sim's robot is built with
// it. Absent (height 0) for a hand-held camera.
#pragma once

#include "common/config_json.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <string>

namespace stairs {

struct MountConfig {
  float height_m = 0.0f;   // m; camera above the ground the carrier stands on; 0 = no mount (hand-held)
  float pitch_deg = 0.0f;  // deg; camera pitch with the carrier on level ground (DESIGN.md: below horizon < 0)
  float roll_deg = 0.0f;   // deg; camera roll with the carrier on level ground

  bool configured() const { return height_m > 0.0f; }

  template <class V>
  void visit(V& v) {
    v("height_m", height_m, 0.0f, 10.0f);
    v("pitch_deg", pitch_deg, -90.0f, 90.0f);
    v("roll_deg", roll_deg, -180.0f, 180.0f);
  }
};

// The "mount" object of a config (any subset of its keys); errors name `file` and the key.
inline MountConfig mount_from_json(const nlohmann::json& object, const std::string& file) {
  return read_config<MountConfig>(object, file, "mount",
                                  " (the top-level 'mount' object: height_m, pitch_deg, roll_deg of the camera on "
                                  "its robot; see config/stairs-sim-robot.json)");
}

// The optical frame (x right, y down, z forward) of a camera in a z-up frame: heading yaw_deg from
// +x (counter-clockwise seen from above), its optical axis pitch_deg above the horizon, turned
// roll_deg about that axis (positive = right side down). Rotates optical vectors into the z-up frame.
inline Eigen::Matrix3d optical_rotation(double yaw_deg, double pitch_deg, double roll_deg) {
  const double rad = M_PI / 180.0;
  Eigen::Matrix3d level;  // at zero yaw, pitch and roll: z forward = +x, x right = -y, y down = -z
  level.col(0) = -Eigen::Vector3d::UnitY();
  level.col(1) = -Eigen::Vector3d::UnitZ();
  level.col(2) = Eigen::Vector3d::UnitX();
  return Eigen::AngleAxisd(yaw_deg * rad, Eigen::Vector3d::UnitZ()).toRotationMatrix() * level *
         Eigen::AngleAxisd(pitch_deg * rad, Eigen::Vector3d::UnitX()).toRotationMatrix() *
         Eigen::AngleAxisd(roll_deg * rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

// The camera's optical frame in its carrier's base frame (REP 103: x forward, y left, z up; the
// origin on the ground straight beneath the camera when the carrier stands level): height_m up
// the base's z axis, pitched and rolled by the mount. Base pose = camera pose * inverse of this.
inline Eigen::Isometry3d camera_in_base(const MountConfig& m) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = optical_rotation(0.0, m.pitch_deg, m.roll_deg);
  T.translation() = Eigen::Vector3d(0.0, 0.0, m.height_m);
  return T;
}

// The base pose of a carrier whose camera is posed at position_m with orientation (optical frame
// -> a z-up frame: the tracker's model, the stair's ground truth), through the mount.
inline Eigen::Isometry3d base_of_camera(const Eigen::Vector3d& position_m, const Eigen::Quaterniond& orientation,
                                        const MountConfig& m) {
  Eigen::Isometry3d camera = Eigen::Isometry3d::Identity();
  camera.linear() = orientation.normalized().toRotationMatrix();
  camera.translation() = position_m;
  return camera * camera_in_base(m).inverse();
}

}  // namespace stairs
