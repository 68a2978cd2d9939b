// Stair-frame geometry the side and top views share: the extent of a step, of
// the whole scene, and the camera's field of view.
#pragma once

#include "common/types.hpp"

#include <Eigen/Geometry>

#include <optional>
#include <vector>

namespace stairs::viewer {

// A step's riser bottom, nosing and tread end in the stair frame (x, z), m.
// An unknown riser height reaches down to the previous tread (or the floor); an
// unknown tread depth is drawn as zero.
struct StepProfile {
  Eigen::Vector2d riser_bottom, nosing, tread_end;
};
std::vector<StepProfile> step_profiles(const Flight& flight);

struct CameraView {
  Eigen::Vector3d position_m;        // stair frame
  Eigen::Quaterniond orientation;    // optical -> stair
};
std::optional<CameraView> model_camera(const StairModel* model);
std::optional<CameraView> truth_camera(const GroundTruthFrame* frame);

// Half field of view, rad: horizontal (u) and vertical (v); 57 x 43 deg (Kinect) without intrinsics.
double half_fov_rad(const Intrinsics* K, bool horizontal);

}  // namespace stairs::viewer
