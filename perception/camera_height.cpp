#include "perception/camera_height.hpp"

#include <algorithm>
#include <cmath>

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

// How far the point beneath the camera (s = t = 0) lies outside an extent; 0 inside it.
float outside_m(const PlaneExtent& e) {
  const float ds = std::max({e.s_min, -e.s_max, 0.0f}), dt = std::max({e.t_min, -e.t_max, 0.0f});
  return std::hypot(ds, dt);
}

// The point straight beneath is in view: the tread-like surface below the camera whose extent holds
// it, or, when none does, comes nearest it within the margin (trimmed extents end short of the
// image's border). Not the lowest one: a camera tipping over a nosing has the next tread down within
// a few centimetres ahead, and took it for its ground (18 cm off on a robot descent). Two surfaces at
// different heights that both hold the point, or tie for nearest, make it unknown.
std::optional<double> surface_straight_beneath(const PlaneSet& ps, const CameraHeightConfig& cfg) {
  const PlaneExtent* best = nullptr;
  float best_out = 0;
  bool ambiguous = false;
  for (size_t i = 0; i < ps.planes.size(); ++i) {
    const PlaneExtent& e = ps.extents[i];
    if (ps.planes[i].kind != PlaneKind::Tread || e.z_mean >= 0) continue;
    const float out = outside_m(e);
    if (out > cfg.view_edge_margin_m) continue;
    if (!best || out < best_out) {
      best = &e;
      best_out = out;
      ambiguous = false;
    } else if (out == best_out && std::abs(best->z_mean - e.z_mean) > cfg.level_tolerance_m) {
      ambiguous = true;
    }
  }
  if (!best || ambiguous) return std::nullopt;
  return -static_cast<double>(best->z_mean);
}

}  // namespace

std::optional<double> camera_height(const PlaneSet& ps, const Intrinsics& K, double pitch_deg, double roll_deg,
                                    const CameraHeightConfig& cfg, const MountConfig& mount) {
  const double below_rad = -pitch_deg * M_PI / 180.0 + std::atan((K.height - 1 - K.cy) / K.fy);
  if (below_rad <= 0) return std::nullopt;
  if (below_rad >= M_PI / 2) return surface_straight_beneath(ps, cfg);
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
