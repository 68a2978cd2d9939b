// Top view of the model's footprint: each tread (landing) as a rectangle,
// the real footprint dashed, the camera with its horizontal field of view.
#pragma once

#include "viewer/config.hpp"
#include "viewer/side_view.hpp"

#include <opencv2/core.hpp>

namespace stairs::viewer {

// Draws on `panel` (CV_8UC3); returns the number of model treads drawn.
int draw_top_view(cv::Mat& panel, const SceneRefs& scene, const ViewerConfig& cfg);

}  // namespace stairs::viewer
