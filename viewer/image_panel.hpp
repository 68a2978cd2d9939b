// Image panel: the depth (or normal) image with the observation's planes
// coloured by kind and its edges overlaid.
#pragma once

#include "common/types.hpp"
#include "viewer/config.hpp"

#include <opencv2/core.hpp>

#include <optional>

namespace stairs::viewer {

// CV_8UC3 colour map of the depth, same size as the image; no measurement = black.
cv::Mat depth_colour(const DepthImage& depth, const ViewerConfig& cfg);
// CV_8UC3 surface normals (camera optical frame) as colour, |n| mapped to 0..255.
cv::Mat normal_colour(const DepthImage& depth, const ViewerConfig& cfg);

// Pixel of a point of the gravity-aligned camera frame (observation frame), or
// nothing when it lies behind the camera.
std::optional<cv::Point2f> project_gravity_point(const Eigen::Vector3f& p_m, const Eigen::Quaterniond& gravity_rotation,
                                                 const Intrinsics& K);

// Draws the observation's planes (filled hull of their projected points, or of
// their corners) and edges on `img`, whose pixels follow intrinsics K.
void draw_observation(cv::Mat& img, const Observation& obs, const Intrinsics& K, const ViewerConfig& cfg);

// The whole panel at cfg.image_width_px x cfg.image_height_px. `depth` may be
// null (no frame yet): the panel then says so and the overlays are skipped.
cv::Mat image_panel(const DepthImage* depth, const Observation* obs, ImageMode mode, const ViewerConfig& cfg);

}  // namespace stairs::viewer
