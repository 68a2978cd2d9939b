#include "perception/camera_height.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace stairs {

namespace {

// The lowest tread-like surface below the camera that meets the image's lowest
// row (its near edge where that row's ray meets its height): seen from there
// on, it may run on beneath the camera.
const PlaneExtent* lowest_at_view_edge(const PlaneSet& ps, double below_rad, const CameraHeightConfig& cfg) {
  const PlaneExtent* lowest = nullptr;
  for (size_t i = 0; i < ps.planes.size(); ++i) {
    const PlaneExtent& e = ps.extents[i];
    if (ps.planes[i].kind != PlaneKind::Tread || e.z_mean >= 0) continue;
    const double view_edge_m = -e.z_mean / std::tan(below_rad);
    if (e.s_min < view_edge_m * (1 + cfg.view_edge_tolerance) + cfg.view_edge_margin_m &&
        (!lowest || e.z_mean < lowest->z_mean))
      lowest = &e;
  }
  return lowest;
}

// The point straight beneath is in view: the level of the grid's cells nearest the plumb line below
// the camera, where cells lie around it (before and behind, left and right) and the nearest agree.
// The planes' extents cannot tell: a robot tipping over a nosing saw the tread it stood on only as a
// strip too small to segment, or nearer than a Kinect v2 measures, and the next tread down began a
// few cm ahead of the plumb line (18 cm off). Cells on one side only are a surface beside the plumb
// line, not beneath it; nearest cells on two levels straddle an edge: unknown.
std::optional<double> height_over_cells_beneath(const NormalGrid& g, const Eigen::Matrix3f& R,
                                                const CameraHeightConfig& cfg) {
  std::vector<std::pair<float, float>> near;  // horizontal distance to the plumb line, height
  Eigen::Vector2f lo(0, 0), hi(0, 0);
  for (size_t c = 0; c < g.points.size(); ++c) {
    if (!g.has_point[c]) continue;
    const Eigen::Vector3f q = R * g.points[c];
    const float d = std::hypot(q.x(), q.y());
    if (q.z() >= 0 || d >= cfg.beneath_radius_m) continue;
    near.emplace_back(d, q.z());
    lo = lo.cwiseMin(q.head<2>());
    hi = hi.cwiseMax(q.head<2>());
  }
  const size_t k = static_cast<size_t>(cfg.beneath_nearest_cells);
  if (near.size() < k || (lo.array() >= 0).any() || (hi.array() <= 0).any()) return std::nullopt;
  std::partial_sort(near.begin(), near.begin() + static_cast<std::ptrdiff_t>(k), near.end());
  std::vector<float> zs;
  for (size_t i = 0; i < k; ++i) zs.push_back(near[i].second);
  std::sort(zs.begin(), zs.end());
  if (zs.back() - zs.front() > cfg.level_tolerance_m) return std::nullopt;
  return -static_cast<double>(zs[k / 2]);
}

}  // namespace

std::optional<double> camera_height(const PlaneSet& ps, const NormalGrid& grid, const Eigen::Matrix3f& R,
                                    const Intrinsics& K, double pitch_deg, double roll_deg,
                                    const CameraHeightConfig& cfg, const MountConfig& mount) {
  const double below_rad = -pitch_deg * M_PI / 180.0 + std::atan((K.height - 1 - K.cy) / K.fy);
  if (below_rad <= 0) return std::nullopt;
  if (below_rad >= M_PI / 2) return height_over_cells_beneath(grid, R, cfg);
  // Out of view, the surface beneath may be the level that fills the image's
  // lowest row or one a riser or more below it: a landing looks like a floor,
  // and a step hides under the view (thesis 4.2). Only a mounted camera on a
  // level carrier settles it: that level at the mount's height is its ground.
  if (!mount.configured()) return std::nullopt;
  if (std::abs(pitch_deg - mount.pitch_deg) > cfg.mount_tilt_tolerance_deg ||
      std::abs(roll_deg - mount.roll_deg) > cfg.mount_tilt_tolerance_deg)
    return std::nullopt;  // the carrier is tilted (on the stair): its ground is not level
  const PlaneExtent* lowest = lowest_at_view_edge(ps, below_rad, cfg);
  if (!lowest || std::abs(-lowest->z_mean - mount.height_m) > cfg.mount_height_tolerance_m) return std::nullopt;
  return -static_cast<double>(lowest->z_mean);
}

}  // namespace stairs
