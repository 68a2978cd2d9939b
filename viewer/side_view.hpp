// Side view (forward x up) of the stair model: one profile segment (riser +
// tread) per step with its riser height and tread depth, the camera with its
// field of view, and the ground-truth profile dashed.
#pragma once

#include "common/types.hpp"
#include "viewer/config.hpp"

#include <opencv2/core.hpp>

#include <vector>

namespace stairs::viewer {

// One step's profile as drawn, px: up the riser to the nosing, then along the tread.
struct ProfileSegment {
  bool truth = false;  // ground truth (dashed) or model
  int flight = 0;
  int step = 0;
  cv::Point riser_bottom, nosing, tread_end;
};

// What the side and top views draw besides the model.
struct SceneRefs {
  const StairModel* model = nullptr;            // may be null
  const GroundTruth* truth = nullptr;           // flights of the real stair, may be null
  const GroundTruthFrame* truth_frame = nullptr;  // the real camera pose, may be null
  const Intrinsics* K = nullptr;                // for the field of view, may be null
};

// +1 when "forward" (the way the camera looks) is the stair frame's +x, -1 when
// it looks down the stair (-x); both views draw forward to the right.
double forward_sign(const SceneRefs& scene);

// Draws on `panel` (CV_8UC3) and returns the step profiles drawn.
std::vector<ProfileSegment> draw_side_view(cv::Mat& panel, const SceneRefs& scene, const ViewerConfig& cfg);

}  // namespace stairs::viewer
