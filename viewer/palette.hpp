// Colours (BGR) shared by every panel, so a kind has one colour everywhere.
#pragma once

#include "common/types.hpp"

#include <opencv2/core.hpp>

namespace stairs::viewer {

inline cv::Scalar kind_colour(PlaneKind k) {
  switch (k) {
    case PlaneKind::Tread: return {40, 200, 40};     // green
    case PlaneKind::Riser: return {230, 140, 30};    // blue
    case PlaneKind::Landing: return {0, 190, 250};   // amber
    case PlaneKind::Other: break;
  }
  return {170, 120, 200};                            // mauve
}

inline cv::Scalar edge_colour(EdgeType t) {
  switch (t) {
    case EdgeType::Convex: return {40, 40, 255};     // red
    case EdgeType::Concave: return {255, 60, 255};   // magenta
    case EdgeType::Unknown: break;
  }
  return {255, 255, 255};
}

inline const cv::Scalar kModelColour{40, 200, 40};   // side/top view profile (tread green)
inline const cv::Scalar kRiserColour{230, 140, 30};
inline const cv::Scalar kTruthColour{200, 200, 200};
inline const cv::Scalar kCameraColour{0, 220, 255};
inline const cv::Scalar kTruthCameraColour{160, 160, 160};
inline const cv::Scalar kTextColour{235, 235, 235};
inline const cv::Scalar kBackground{32, 32, 32};
inline const cv::Scalar kGridColour{55, 55, 55};

}  // namespace stairs::viewer
