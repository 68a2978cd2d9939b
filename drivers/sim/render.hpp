// The simulated Kinect v1: renders a Scene from a camera pose into a depth
// image with the sensor's effects (each a switch), and the exact ground truth
// of the frame.
#pragma once

#include "drivers/sim/geometry.hpp"
#include "drivers/sim/raster.hpp"
#include "drivers/sim/scene.hpp"
#include "drivers/sim/sensor.hpp"

#include "common/types.hpp"

#include <cstdint>

namespace stairs::sim {

class Renderer {
 public:
  Renderer(const Scene& scene, const Intrinsics& K, const SensorModel& sensor, uint64_t seed);

  // Depth in millimetres (depth_scale 0.001). Deterministic in (seed, seq):
  // the noise of frame `seq` does not depend on which frames came before.
  DepthImage render(const Eigen::Isometry3d& camera_optical_in_stair, int64_t utime, int32_t seq);

  // Pose scalars of DESIGN.md and visible_steps: steps whose riser or tread has
  // at least visible_min_pixels() valid pixels in `rendered`.
  GroundTruthFrame truth(const Eigen::Isometry3d& camera_optical_in_stair, double timestamp_s,
                         const DepthImage& rendered) const;

  GroundTruth stair_truth() const;  // flights and scene name; no frames

  // 500 at 640x480 (DESIGN.md), scaled with the pixel count at other
  // resolutions so that it means the same visible area.
  int visible_min_pixels() const;

  const Scene& scene() const { return scene_; }
  const Geometry& geometry() const { return geometry_; }
  const Intrinsics& intrinsics() const { return K_; }
  const SensorModel& sensor() const { return sensor_; }

 private:
  Scene scene_;
  Geometry geometry_;
  Intrinsics K_;
  Intrinsics projector_K_;
  SensorModel sensor_;
  std::vector<uint8_t> dark_;  // per face: absorbs the IR (Scene::dark_treads)
  uint64_t seed_;
  ZBuffer camera_zb_, projector_zb_;
  Eigen::Isometry3d last_pose_ = Eigen::Isometry3d::Identity();  // of camera_zb_
  bool have_last_pose_ = false;
  std::vector<float> depth_m_, scratch_m_;
};

}  // namespace stairs::sim
