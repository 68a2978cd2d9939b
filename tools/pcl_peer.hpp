// The peer reference of stairs-bench: PCL's organized plane extraction
// (IntegralImageNormalEstimation + OrganizedMultiPlaneSegmentation), plane
// extraction only, with PCL's usual parameters for Kinect-like data.
#pragma once

#include "common/types.hpp"

#include <memory>

namespace stairs::eval {

struct PclPeerConfig {
  float max_depth_change_factor = 0.02f;  // normal estimation: depth discontinuity, m
  float normal_smoothing_size_px = 10.0f;
  int min_inliers_640x480 = 1000;          // per plane, scaled with the pixel count
  double angular_threshold_deg = 3.0;
  double distance_threshold_m = 0.02;
};

class PclPeer {
 public:
  explicit PclPeer(PclPeerConfig config = {});
  ~PclPeer();
  // Extracts planar regions; returns their number.
  size_t extract_planes(const DepthImage& image);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace stairs::eval
