#include "perception/gravity.hpp"

#include <cmath>

namespace stairs {

std::optional<Eigen::Vector3f> estimate_up(const std::vector<Segment>& segments, const PerceptionConfig& cfg) {
  const float deg = static_cast<float>(M_PI) / 180.0f;
  const float cos_tilt = std::cos(cfg.max_tilt_from_image_up_deg * deg);
  const float cos_par = std::cos(cfg.parallel_deg * deg);
  const Eigen::Vector3f image_up(0, -1, 0);
  double best_score = 0;
  int best = -1;
  for (size_t i = 0; i < segments.size(); ++i) {
    const Eigen::Vector3f& ni = segments[i].normal;
    if (ni.dot(image_up) < cos_tilt) continue;
    double score = 0;
    for (const Segment& s : segments)
      if (s.normal.dot(ni) > cos_par) score += static_cast<double>(s.cells.size());
    if (score > best_score) {
      best_score = score;
      best = static_cast<int>(i);
    }
  }
  if (best < 0) return std::nullopt;
  // Weighted by support: large planes have the best-determined normals.
  Eigen::Vector3f up = Eigen::Vector3f::Zero();
  for (const Segment& s : segments)
    if (s.normal.dot(segments[best].normal) > cos_par) up += static_cast<float>(s.cells.size()) * s.normal;
  return up.normalized();
}

CameraPose pose_from_up(const Eigen::Vector3f& up_optical) {
  const Eigen::Vector3d up = up_optical.cast<double>().normalized();
  CameraPose pose;
  pose.valid = true;
  pose.pitch_deg = std::asin(std::clamp(up.z(), -1.0, 1.0)) * 180.0 / M_PI;
  pose.roll_deg = std::atan2(-up.x(), -up.y()) * 180.0 / M_PI;
  // Forward = optical axis levelled; looking straight down, the image top.
  Eigen::Vector3d fwd = Eigen::Vector3d::UnitZ() - up.z() * up;
  if (fwd.norm() < 0.1) fwd = -Eigen::Vector3d::UnitY() + up.y() * up;
  fwd.normalize();
  Eigen::Matrix3d R;
  R.row(0) = fwd.transpose();
  R.row(1) = up.cross(fwd).transpose();
  R.row(2) = up.transpose();
  pose.gravity_rotation = Eigen::Quaterniond(R).normalized();
  return pose;
}

}  // namespace stairs
