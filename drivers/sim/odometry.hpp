// Simulated odometry (issue 15): the camera's pose in a drifting odometry
// frame, as a robot's wheel, leg or visual-inertial odometry gives it. The
// true motion between samples is scaled and rotated by slowly wandering
// errors, so the pose drifts but never jumps; the odometry frame starts at an
// arbitrary place and heading (nothing may assume it is the stair frame).
#pragma once

#include "drivers/sim/rng.hpp"
#include "drivers/sim/trajectory.hpp"

#include "common/types.hpp"

#include <vector>

namespace stairs::sim {

struct OdometryNoise {
  double rate_hz = 100.0;                 // Hz; samples per second (wheel/leg odometry: 50-200)
  double scale_error = 0.01;              // fraction; distance scale error, drawn within +-
  double position_walk_m = 0.002;         // m/sqrt(s); random walk of the position increments
  double yaw_bias_deg_per_s = 0.1;        // deg/s; heading drift rate, drawn within +-
  double yaw_walk_deg = 0.05;             // deg/sqrt(s); random walk of the heading error
};

class OdometrySim {
 public:
  OdometrySim(const Trajectory& trajectory, const OdometryNoise& noise, uint64_t seed);
  // The samples from the last one given up to t_s (trajectory time) inclusive;
  // utime of trajectory time 0 is utime0.
  std::vector<OdometrySample> until(double t_s, int64_t utime0);

 private:
  void step_to(double t_s);

  const Trajectory& trajectory_;
  OdometryNoise noise_;
  Rng rng_;
  double scale_, yaw_bias_rad_per_s_;
  int next_ = 0;  // index of the next sample (time next_ / rate)
  double t_ = 0.0, yaw_error_rad_ = 0.0;
  Eigen::Isometry3d true_;  // true pose at t_
  Eigen::Vector3d position_m_;
  Eigen::Vector3d origin_m_;  // where the odometry frame's origin lies (drawn)
};

}  // namespace stairs::sim
