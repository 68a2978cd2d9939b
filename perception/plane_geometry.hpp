// Stage 4: planes in the gravity-aligned frame: histogram merge, horizontal /
// vertical classification, bounding boxes (thesis Algorithm 5) and extents.
#pragma once

#include "perception/region_growing.hpp"

#include <cmath>
#include <optional>
#include <utility>
#include <vector>

namespace stairs {

// A tread's extent along the stair in lateral strips: strip k covers t from t0 + k * width; NaN where
// none of its cells lies. A level runs on beside a step wherever the flight is narrower than what was
// seen of it (the floor beside an open-sided flight, or of a room wider than the flight, reaches past
// the first riser); under the step it ends at the riser's foot.
struct Strips {
  static constexpr int kMax = 64;  // strips per plane (a wider plane gets wider strips)
  float t0 = 0, width = 0;
  std::vector<float> s_min{}, s_max{};
  // The median of the extents of the strips whose middle lies in [t_lo, t_hi]; none if no such strip.
  std::optional<std::pair<float, float>> across(float t_lo, float t_hi) const;
};

// Extent of a plane in the stair-aligned frame (s along the stair's
// ascending/descending axis, t lateral/left, z up), trimmed percentiles, m.
struct PlaneExtent {
  float s_min = 0, s_max = 0, t_min = 0, t_max = 0, z_min = 0, z_max = 0;
  float s_mean = 0, z_mean = 0;  // the cells' mean; a riser's s_mean is its face: the median of its
                                 // middle rows (PlaneGeometryConfig::riser_face_band_fraction)
  bool top_in_view = true;     // false when the plane's highest cells lie on the grid's top border or, for a
                               // riser, a nearer surface hides them (occluder_min_gap_m)
  bool bottom_in_view = true;  // false when its lowest cells lie on the grid's bottom border
  Strips strips{};             // a tread's (empty for other planes)
};

struct PlaneSet {
  std::vector<Plane> planes;        // gravity-aligned camera frame
  std::vector<PlaneExtent> extents;  // same order
  float yaw_rad = 0;                 // stair axis relative to camera forward
  bool axis_from_risers = false;     // yaw_rad from vertical planes facing the camera (else given, or 0)
  // The axis the planes facing the camera that are taller than a rise give (walls, an end wall, a
  // cabinet, a person): what the pipeline falls back on where neither risers nor nosings give one.
  std::optional<float> tall_facing_yaw_rad;
  // Stair-aligned (s, t, z) -> gravity-aligned camera frame.
  Eigen::Vector3f to_camera(float s, float t, float z) const;
  // Gravity-aligned camera frame -> position along the stair axis (s).
  float axial(const Eigen::Vector3d& p) const;
  // Gravity-aligned camera frame -> lateral position across the stair (t, left).
  float lateral(const Eigen::Vector3d& p) const;
};

// Merges the segments (optical frame) rotated by `gravity` (optical ->
// gravity-aligned) into planes: horizontal ones binned by height, vertical
// ones by depth along their normal, one cross-bin merge per plane; at most
// caps.max_planes, with point samples of at most caps.max_*_points. The stair axis is the one
// `axis_yaw_rad` gives, else from the vertical planes facing the camera (risers), else forward.
PlaneSet plane_geometry(const NormalGrid& grid, const std::vector<Segment>& segments,
                        const Eigen::Matrix3f& gravity, const PlaneGeometryConfig& cfg, const OutputConfig& caps,
                        std::optional<float> axis_yaw_rad = std::nullopt);

// The one riser search of steps and reconstruction: of the segmented risers
// whose face (s_mean) lies within [s_lo, s_hi], at least `min_width_m` wide
// (a riser spans its step; a baluster or post facing the camera is narrower),
// and whose extent satisfies `fits`, the one `better` (a, b) prefers; -1 if none.
template <class Fits, class Better>
int find_riser(const PlaneSet& ps, float s_lo, float s_hi, float min_width_m, Fits fits, Better better) {
  int best = -1;
  for (size_t i = 0; i < ps.planes.size(); ++i) {
    const PlaneExtent& e = ps.extents[i];
    if (ps.planes[i].kind != PlaneKind::Riser || e.s_mean < s_lo || e.s_mean > s_hi || e.t_max - e.t_min < min_width_m ||
        !fits(e))
      continue;
    if (best < 0 || better(e, ps.extents[static_cast<size_t>(best)])) best = static_cast<int>(i);
  }
  return best;
}

// ... nearest to s_ref.
template <class Fits>
int find_riser(const PlaneSet& ps, float s_lo, float s_hi, float s_ref, float min_width_m, Fits fits) {
  return find_riser(ps, s_lo, s_hi, min_width_m, fits, [s_ref](const PlaneExtent& a, const PlaneExtent& b) {
    return std::abs(a.s_mean - s_ref) < std::abs(b.s_mean - s_ref);
  });
}

// At most max_points of `cells`, spatially even on the image grid.
std::vector<int> grid_subsample(const NormalGrid& grid, const std::vector<int>& cells, int max_points);

}  // namespace stairs
