// Gravity from an optional IMU (issue 15). A complementary filter keeps the
// specific force of gravity in the camera optical frame: the gyroscope turns
// it between samples, the accelerometer's readings are low-passed into it with
// a time constant long enough that walking accelerations average out.
// The planes' up (thesis Algorithm 4) stays the measurement where the two
// agree: level floors and treads give it to a hundredth of a degree. Where
// the planes are tilted against gravity (a ramp) the IMU's up is used; where
// they disagree by more than any ramp people walk, the IMU is rejected.
#pragma once

#include "common/types.hpp"
#include "perception/config.hpp"

#include <Eigen/Geometry>

#include <optional>
#include <string>

namespace stairs {

// IMU frame -> camera optical frame from the config.
Eigen::Matrix3d imu_to_camera(const ImuConfig& c);
// A sample of the IMU's frame in the camera optical frame.
ImuSample turned(const ImuSample& s, const Eigen::Matrix3d& imu_to_camera);

class ImuGravity {
 public:
  explicit ImuGravity(const ImuConfig& c) : c_(c) {}
  // One sample in the camera optical frame, in time order (an older or equal
  // one is dropped and counted; after a gap longer than max_age_s, or a step
  // back in time longer than that, the filter starts again from the
  // accelerometer).
  void add(const ImuSample& s);
  // The filter's up (unit, camera optical frame) for a frame at utime: none
  // unless warmed up and fresh.
  std::optional<Eigen::Vector3f> up_at(int64_t utime) const;
  int64_t dropped() const { return dropped_; }

 private:
  ImuConfig c_;
  Eigen::Vector3d gravity_ = Eigen::Vector3d::Zero();  // low-passed specific force, camera optical frame
  int64_t first_utime_ = 0, last_utime_ = 0;
  bool started_ = false;
  int64_t dropped_ = 0;
};

// How the frame's up was chosen.
struct FusedUp {
  std::optional<Eigen::Vector3f> up;
  std::string note;  // empty when the planes' up is used as without an IMU
};

// The frame's up from the planes' and the IMU's (either may be absent).
FusedUp fuse_up(const std::optional<Eigen::Vector3f>& planes, const std::optional<Eigen::Vector3f>& imu,
                const ImuConfig& c);

}  // namespace stairs
