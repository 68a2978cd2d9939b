#include "tools/pcl_peer.hpp"

#include "common/cloud.hpp"

#include <pcl/features/integral_image_normal.h>
#include <pcl/segmentation/organized_multi_plane_segmentation.h>

#include <cmath>

namespace stairs::eval {

struct PclPeer::Impl {
  PclPeerConfig config;
  pcl::IntegralImageNormalEstimation<pcl::PointXYZ, pcl::Normal> normals;
  pcl::OrganizedMultiPlaneSegmentation<pcl::PointXYZ, pcl::Normal, pcl::Label> planes;
};

PclPeer::PclPeer(PclPeerConfig config) : impl_(std::make_unique<Impl>()) {
  impl_->config = config;
  impl_->normals.setNormalEstimationMethod(impl_->normals.AVERAGE_3D_GRADIENT);
  impl_->normals.setMaxDepthChangeFactor(config.max_depth_change_factor);
  impl_->normals.setNormalSmoothingSize(config.normal_smoothing_size_px);
  impl_->planes.setAngularThreshold(config.angular_threshold_deg * M_PI / 180.0);
  impl_->planes.setDistanceThreshold(config.distance_threshold_m);
}

PclPeer::~PclPeer() = default;

size_t PclPeer::extract_planes(const DepthImage& image) {
  const auto cloud = organized_cloud(image);
  pcl::PointCloud<pcl::Normal>::Ptr normals(new pcl::PointCloud<pcl::Normal>);
  impl_->normals.setInputCloud(cloud);
  impl_->normals.compute(*normals);
  const double pixels = double(image.K.width) * image.K.height;
  impl_->planes.setMinInliers(
      static_cast<unsigned>(std::lround(impl_->config.min_inliers_640x480 * pixels / (640.0 * 480.0))));
  impl_->planes.setInputNormals(normals);
  impl_->planes.setInputCloud(cloud);
  std::vector<pcl::PlanarRegion<pcl::PointXYZ>, Eigen::aligned_allocator<pcl::PlanarRegion<pcl::PointXYZ>>> regions;
  impl_->planes.segmentAndRefine(regions);
  return regions.size();
}

}  // namespace stairs::eval
