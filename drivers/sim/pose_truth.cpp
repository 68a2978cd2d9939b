#include "drivers/sim/pose_truth.hpp"

#include <cmath>
#include <limits>

namespace stairs::sim {
namespace {
constexpr double kDeg = 180.0 / M_PI;
}

double pitch_deg(const Eigen::Isometry3d& T) {
  const Eigen::Vector3d z = T.linear().col(2);
  return std::atan2(z.z(), std::hypot(z.x(), z.y())) * kDeg;
}

double roll_deg(const Eigen::Isometry3d& T) {
  // Right side down = the optical x axis dips below the horizon; measured
  // against the image's down axis so that it is independent of the pitch.
  const Eigen::Vector3d x = T.linear().col(0), y = T.linear().col(1);
  return std::atan2(-x.z(), -y.z()) * kDeg;
}

double height_m(const Scene& s, const Eigen::Isometry3d& T) {
  const Eigen::Vector3d p = T.translation();
  return p.z() - surface_height_m(s, p.x(), p.y());
}

std::optional<double> distance_m(const Scene& s, const Eigen::Isometry3d& T) {
  const std::vector<StepGeometry> steps = step_geometry(s);
  if (steps.empty()) return std::nullopt;
  const double x = T.translation().x();
  const bool up = T.linear().col(2).x() >= 0.0;
  std::optional<double> best;
  for (size_t i = 0; i < steps.size();) {
    // One flight: from its first riser to the nosing of its landing.
    size_t j = i;
    while (!steps[j].landing) ++j;
    const double bottom_x = steps[i].riser_x_m;
    const double top_x = steps[j].riser_x_m - s.nosing_m;
    if (x >= bottom_x && x < top_x) return std::nullopt;  // over the flight
    const double d = up ? bottom_x - x : x - top_x;
    if (d >= 0.0 && (!best || d < *best)) best = d;
    i = j + 1;
  }
  return best;
}

}  // namespace stairs::sim
