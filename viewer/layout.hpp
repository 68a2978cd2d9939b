// The viewer's one window: image panel left, side view over top view right,
// status bar along the bottom.
#pragma once

#include "viewer/config.hpp"
#include "viewer/side_view.hpp"
#include "viewer/status_bar.hpp"

#include <opencv2/core.hpp>

#include <vector>

namespace stairs::viewer {

// Everything one view shows; every pointer may be null.
struct ViewInput {
  const DepthImage* depth = nullptr;  // the frame behind `observation` (or the latest)
  const Observation* observation = nullptr;
  const StairModel* model = nullptr;
  const GroundTruth* truth = nullptr;
  const GroundTruthFrame* truth_frame = nullptr;
  ImageMode mode = ImageMode::Depth;
  ViewStats stats;
};

struct Layout {
  cv::Rect image, side, top, status;
  cv::Size size;
};
Layout layout(const ViewerConfig& cfg);

// Draws the whole view; `segments` (optional) receives the side view's profile segments
// in window pixels.
cv::Mat compose_view(const ViewInput& in, const ViewerConfig& cfg, std::vector<ProfileSegment>* segments = nullptr);

}  // namespace stairs::viewer
