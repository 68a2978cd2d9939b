#include "viewer/image_panel.hpp"

#include "common/cloud.hpp"
#include "viewer/palette.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace stairs::viewer {

cv::Mat depth_colour(const DepthImage& depth, const ViewerConfig& cfg) {
  const cv::Mat z = depth_metres_mat(depth);
  cv::Mat grey(z.size(), CV_8UC1);
  const double span = std::max(1e-3, cfg.depth_max_m - cfg.depth_min_m);
  for (int v = 0; v < z.rows; ++v)
    for (int u = 0; u < z.cols; ++u) {
      const float m = z.at<float>(v, u);
      const double t = std::clamp((cfg.depth_max_m - m) / span, 0.0, 1.0);  // near = bright
      grey.at<uint8_t>(v, u) = std::isfinite(m) ? static_cast<uint8_t>(40 + 170 * t) : 0;
    }
  cv::Mat colour;
  cv::applyColorMap(grey, colour, cv::COLORMAP_BONE);
  colour.setTo(cv::Scalar::all(0), grey == 0);
  return colour;
}

cv::Mat normal_colour(const DepthImage& depth, const ViewerConfig& cfg) {
  const Intrinsics& K = depth.K;
  const int s = std::max(1, cfg.normal_step_px);
  cv::Mat out(K.height, K.width, CV_8UC3, cv::Scalar::all(0));
  auto point = [&](int u, int v) { return back_project(K, u, v, depth.metres(u, v)); };
  for (int v = s; v < K.height - s; ++v)
    for (int u = s; u < K.width - s; ++u) {
      if (depth.metres(u, v) <= 0 || depth.metres(u + s, v) <= 0 || depth.metres(u - s, v) <= 0 ||
          depth.metres(u, v + s) <= 0 || depth.metres(u, v - s) <= 0)
        continue;
      const Eigen::Vector3f du = point(u + s, v) - point(u - s, v), dv = point(u, v + s) - point(u, v - s);
      Eigen::Vector3f n = dv.cross(du);  // points towards the camera (-z)
      if (n.squaredNorm() < 1e-12f) continue;
      n.normalize();
      out.at<cv::Vec3b>(v, u) = {static_cast<uint8_t>(127.5f * (n.z() + 1)), static_cast<uint8_t>(127.5f * (n.y() + 1)),
                                 static_cast<uint8_t>(127.5f * (n.x() + 1))};
    }
  return out;
}

std::optional<cv::Point2f> project_gravity_point(const Eigen::Vector3f& p_m, const Eigen::Quaterniond& gravity_rotation,
                                                 const Intrinsics& K) {
  const Eigen::Vector3f c = gravity_rotation.cast<float>().conjugate() * p_m;  // back to the optical frame
  if (c.z() < 1e-3f) return std::nullopt;
  return cv::Point2f(static_cast<float>(K.fx * c.x() / c.z() + K.cx), static_cast<float>(K.fy * c.y() / c.z() + K.cy));
}

namespace {

// Projected outline of a plane: the hull of its point sample, else its corners.
std::vector<cv::Point> plane_outline(const Plane& plane, const Eigen::Quaterniond& R, const Intrinsics& K) {
  std::vector<cv::Point2f> px;
  auto add = [&](const Eigen::Vector3f& p) {
    if (auto q = project_gravity_point(p, R, K)) px.push_back(*q);
  };
  if (plane.points.size() >= 3) {
    for (const auto& p : plane.points) add(p);
  } else {
    for (const auto& p : plane.corners) add(p);
  }
  std::vector<cv::Point> hull;
  if (px.size() < 3) return hull;
  std::vector<cv::Point2f> hull_f;
  cv::convexHull(px, hull_f);
  for (const auto& p : hull_f) hull.emplace_back(cvRound(p.x), cvRound(p.y));
  return hull;
}

}  // namespace

void draw_observation(cv::Mat& img, const Observation& obs, const Intrinsics& K, const ViewerConfig& cfg) {
  const Eigen::Quaterniond& R = obs.camera.gravity_rotation;
  const int thick = std::max(1, img.cols / 320);
  std::vector<std::vector<cv::Point>> outlines;
  cv::Mat fill = img.clone();
  for (const Plane& plane : obs.planes) {
    outlines.push_back(plane_outline(plane, R, K));
    if (outlines.back().size() >= 3) cv::fillConvexPoly(fill, outlines.back(), kind_colour(plane.kind), cv::LINE_AA);
  }
  cv::addWeighted(fill, cfg.fill_alpha, img, 1.0 - cfg.fill_alpha, 0.0, img);
  for (size_t i = 0; i < obs.planes.size(); ++i)
    if (outlines[i].size() >= 3)
      cv::polylines(img, outlines[i], true, kind_colour(obs.planes[i].kind), thick, cv::LINE_AA);
  for (const Edge& e : obs.edges) {
    const auto a = project_gravity_point(e.start, R, K), b = project_gravity_point(e.end, R, K);
    if (a && b) cv::line(img, *a, *b, edge_colour(e.type), thick + 1, cv::LINE_AA);
  }
}

cv::Mat image_panel(const DepthImage* depth, const Observation* obs, ImageMode mode, const ViewerConfig& cfg) {
  cv::Mat panel(cfg.image_height_px, cfg.image_width_px, CV_8UC3, kBackground);
  if (!depth || depth->K.width <= 0 || depth->depth.empty()) {
    cv::putText(panel, "waiting for a depth frame", {20, panel.rows / 2}, cv::FONT_HERSHEY_SIMPLEX, 0.7, kTextColour, 1,
                cv::LINE_AA);
    return panel;
  }
  const cv::Mat src = mode == ImageMode::Normals ? normal_colour(*depth, cfg) : depth_colour(*depth, cfg);
  // Fit the image into the panel, keeping its aspect ratio.
  const double s = std::min(double(panel.cols) / src.cols, double(panel.rows) / src.rows);
  const cv::Size size(std::max(1, int(src.cols * s)), std::max(1, int(src.rows * s)));
  cv::Mat roi = panel(cv::Rect((panel.cols - size.width) / 2, (panel.rows - size.height) / 2, size.width, size.height));
  cv::resize(src, roi, size, 0, 0, cv::INTER_NEAREST);
  if (obs) draw_observation(roi, *obs, scale_intrinsics(depth->K, size.width, size.height), cfg);
  return panel;
}

}  // namespace stairs::viewer
