// Views of a depth image: metric cv::Mat, organized PCL cloud, back-projection.
#pragma once

#include "common/types.hpp"

#include <opencv2/core.hpp>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

namespace stairs {

// CV_16UC1 header over the image's buffer (no copy; valid while img lives).
cv::Mat depth_raw_mat(const DepthImage& img);

// CV_32FC1 depth in metres along z, NaN where there is no measurement.
cv::Mat depth_metres_mat(const DepthImage& img);

// Organized cloud (width x height) in the camera optical frame, metres, NaN
// where there is no measurement.
pcl::PointCloud<pcl::PointXYZ>::Ptr organized_cloud(const DepthImage& img);

// Back-projects pixel (u, v) at depth z (m) into the camera optical frame.
inline Eigen::Vector3f back_project(const Intrinsics& K, float u, float v, float z) {
  return {static_cast<float>((u - K.cx) / K.fx) * z, static_cast<float>((v - K.cy) / K.fy) * z, z};
}

// Intrinsics scaled to another resolution (e.g. 640x480 -> 320x240).
Intrinsics scale_intrinsics(const Intrinsics& K, int width, int height);

}  // namespace stairs
