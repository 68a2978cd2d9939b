// The perception pipeline: one depth frame in, one stair observation out
// (gravity-aligned camera frame: x forward, y left, z up, camera centre origin).
#pragma once

#include "common/types.hpp"
#include "perception/bridged_surfaces.hpp"
#include "perception/concave_corners.hpp"
#include "perception/config.hpp"
#include "perception/imu_gravity.hpp"
#include "perception/normals.hpp"

#include <optional>
#include <vector>

namespace stairs {

class Pipeline {
 public:
  explicit Pipeline(PerceptionConfig cfg = {});
  // Never throws on bad input: an unusable frame gives camera.valid = false,
  // direction None and a status naming the reason. Frames of one stream come
  // in order: the last up (unless gravity.prior_max_gap_s passed between two
  // frames) is the gravity prior.
  Observation process(const DepthImage& frame);
  const PerceptionConfig& config() const { return cfg_; }
  // Optional IMU samples in the camera optical frame (imu_to_camera applied),
  // in time order, before the frames they precede: where fresh, its gravity
  // is fused with the planes' (perception/imu_gravity.hpp).
  void add_imu(const ImuSample& s) { imu_.add(s); }
  int64_t dropped_imu() const { return imu_.dropped(); }

 private:
  PerceptionConfig cfg_;
  NormalGrid grid_;          // reused buffers
  std::vector<int> labels_;  // reused buffers
  BridgedSurfacesScratch bridged_;  // reused buffers
  ConcaveCornersScratch corners_;  // reused buffers
  std::optional<Eigen::Vector3f> up_prior_;  // optical frame: the last frame's up that had one
  int64_t last_utime_ = 0;      // the previous usable frame's
  int64_t measured_utime_ = 0;  // the last frame whose planes measured its pitch (none carried)
  ImuGravity imu_;
};

}  // namespace stairs
