// Simulated IMU (issue 15): specific force and angular rate of the camera's
// true motion along the trajectory, in the camera optical frame (the IMU is
// mounted aligned with the camera), with a per-run bias and white noise as a
// consumer MEMS IMU has them. Motion acceleration (gait bounce, sway, the
// walk's speed changes) is in it, as on a real carrier.
#pragma once

#include "drivers/sim/rng.hpp"
#include "drivers/sim/trajectory.hpp"

#include "common/types.hpp"

#include <vector>

namespace stairs::sim {

struct ImuNoise {
  double rate_hz = 200.0;               // Hz; samples per second (100-400 for robot IMUs)
  double accel_bias_mps2 = 0.05;        // m/s^2; per-axis bias, drawn within +- (0.3 deg of tilt)
  double accel_noise_mps2 = 0.02;       // m/s^2; white noise per sample (150 ug/sqrt(Hz) at 200 Hz)
  double gyro_bias_radps = 0.005;       // rad/s; per-axis bias, drawn within +- (0.3 deg/s)
  double gyro_noise_radps = 0.0025;     // rad/s; white noise per sample (0.01 deg/s/sqrt(Hz) at 200 Hz)
};

class ImuSim {
 public:
  ImuSim(const Trajectory& trajectory, const ImuNoise& noise, uint64_t seed);
  // The samples from the last one given up to t_s (trajectory time) inclusive;
  // utime of trajectory time 0 is utime0.
  std::vector<ImuSample> until(double t_s, int64_t utime0);

 private:
  ImuSample measure(double t_s);

  const Trajectory& trajectory_;
  ImuNoise noise_;
  Rng rng_;
  Eigen::Vector3d accel_bias_, gyro_bias_;
  int next_ = 0;
};

}  // namespace stairs::sim
