#include "common/cloud.hpp"

#include <limits>

namespace stairs {

cv::Mat depth_raw_mat(const DepthImage& img) {
  return cv::Mat(img.K.height, img.K.width, CV_16UC1, const_cast<uint16_t*>(img.depth.data()));
}

cv::Mat depth_metres_mat(const DepthImage& img) {
  cv::Mat m(img.K.height, img.K.width, CV_32FC1);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float scale = static_cast<float>(img.depth_scale);
  for (int v = 0; v < img.K.height; ++v) {
    const uint16_t* src = img.depth.data() + static_cast<size_t>(v) * img.K.width;
    float* dst = m.ptr<float>(v);
    for (int u = 0; u < img.K.width; ++u) dst[u] = src[u] ? src[u] * scale : nan;
  }
  return m;
}

pcl::PointCloud<pcl::PointXYZ>::Ptr organized_cloud(const DepthImage& img) {
  auto cloud = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>(img.K.width, img.K.height);
  cloud->is_dense = false;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float scale = static_cast<float>(img.depth_scale);
  for (int v = 0; v < img.K.height; ++v) {
    for (int u = 0; u < img.K.width; ++u) {
      const uint16_t d = img.depth[static_cast<size_t>(v) * img.K.width + u];
      pcl::PointXYZ& p = cloud->at(u, v);
      if (d == 0) {
        p.x = p.y = p.z = nan;
        continue;
      }
      p.getVector3fMap() = back_project(img.K, static_cast<float>(u), static_cast<float>(v), d * scale);
    }
  }
  return cloud;
}

Intrinsics scale_intrinsics(const Intrinsics& K, int width, int height) {
  const double sx = static_cast<double>(width) / K.width;
  const double sy = static_cast<double>(height) / K.height;
  Intrinsics out = K;
  out.width = width;
  out.height = height;
  out.fx = K.fx * sx;
  out.fy = K.fy * sy;
  // Pixel centres: (c + 0.5) scales, not c.
  out.cx = (K.cx + 0.5) * sx - 0.5;
  out.cy = (K.cy + 0.5) * sy - 0.5;
  return out;
}

}  // namespace stairs
