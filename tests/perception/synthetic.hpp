// Analytic depth images for the unit tests: a camera at height h with the
// given pitch and roll over a horizontal floor, optionally with box steps.
#pragma once

#include "common/types.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <limits>

namespace stairs::test {

// Optical -> world (x forward, y left, z up) rotation of a camera with pitch
// (optical axis above the horizon) and roll (right side down).
inline Eigen::Matrix3d optical_to_world(double pitch_deg, double roll_deg) {
  Eigen::Matrix3d base;  // optical x right, y down, z forward in world axes
  base.col(0) = -Eigen::Vector3d::UnitY();
  base.col(1) = -Eigen::Vector3d::UnitZ();
  base.col(2) = Eigen::Vector3d::UnitX();
  const Eigen::Matrix3d pitch(Eigen::AngleAxisd(-pitch_deg * M_PI / 180, Eigen::Vector3d::UnitY()));
  const Eigen::Matrix3d roll(Eigen::AngleAxisd(roll_deg * M_PI / 180, Eigen::Vector3d::UnitZ()));
  return pitch * base * roll;
}

// Floor at z = -height_m; `steps` ascending steps starting at x = first_riser_m, `half_width_m` to
// either side of the camera (the floor beside a narrower flight runs on; its outer sides face away).
inline DepthImage render_stairs(int w, int h, double pitch_deg, double roll_deg, double height_m, int steps,
                                double first_riser_m = 1.5, double riser_m = 0.17, double tread_m = 0.28,
                                double half_width_m = std::numeric_limits<double>::infinity()) {
  DepthImage img;
  img.K = {w, h, 525.0 * w / 640, 525.0 * w / 640, (w - 1) / 2.0, (h - 1) / 2.0};
  img.depth.assign(static_cast<size_t>(w) * h, 0);
  const Eigen::Matrix3d R = optical_to_world(pitch_deg, roll_deg);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const Eigen::Vector3d ray_o((u - img.K.cx) / img.K.fx, (v - img.K.cy) / img.K.fy, 1.0);
      const Eigen::Vector3d d = R * ray_o;  // world direction, z-component of the optical ray is 1
      double best = std::numeric_limits<double>::infinity();
      auto hit = [&](double t) {
        if (t > 0 && t < best) best = t;
      };
      // Floor and treads (horizontal), risers (vertical, facing -x).
      for (int k = 0; k <= steps; ++k) {
        const double z = -height_m + k * riser_m;
        const double x0 = k == 0 ? -1e9 : first_riser_m + (k - 1) * tread_m;
        const double x1 = k == steps ? (steps ? 1e9 : 1e9) : first_riser_m + k * tread_m;
        if (d.z() < 0) {
          const double t = z / d.z();
          const double x = t * d.x();
          const bool beside = std::abs(t * d.y()) > half_width_m;
          if (beside ? k == 0 : x >= x0 && x < x1) hit(t);
        }
        if (k < steps && d.x() > 0) {
          const double t = x1 / d.x();
          const double zz = t * d.z();
          if (zz >= z && zz < z + riser_m && std::abs(t * d.y()) <= half_width_m) hit(t);
        }
      }
      if (std::isfinite(best) && best < 10) img.depth[static_cast<size_t>(v) * w + u] = static_cast<uint16_t>(best * 1000);
    }
  return img;
}

// A corridor: walls at y = +-half_width_m, and a floor at z = -height_m only
// when `floor` (without it the camera sees walls alone, as over a descent whose
// treads lie beyond range).
inline DepthImage render_corridor(int w, int h, double pitch_deg, double height_m, double half_width_m, bool floor) {
  DepthImage img;
  img.K = {w, h, 525.0 * w / 640, 525.0 * w / 640, (w - 1) / 2.0, (h - 1) / 2.0};
  img.depth.assign(static_cast<size_t>(w) * h, 0);
  const Eigen::Matrix3d R = optical_to_world(pitch_deg, 0.0);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const Eigen::Vector3d d = R * Eigen::Vector3d((u - img.K.cx) / img.K.fx, (v - img.K.cy) / img.K.fy, 1.0);
      double t = std::numeric_limits<double>::infinity();
      if (d.y() != 0) t = std::min(t, (d.y() > 0 ? half_width_m : -half_width_m) / d.y());
      const double t_floor = d.z() < 0 ? -height_m / d.z() : std::numeric_limits<double>::infinity();
      if (t_floor < t) t = floor ? t_floor : std::numeric_limits<double>::infinity();
      if (t < 4.0) img.depth[static_cast<size_t>(v) * w + u] = static_cast<uint16_t>(t * 1000);
    }
  return img;
}

}  // namespace stairs::test
