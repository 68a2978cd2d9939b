#include "tracker/nosing_overhang.hpp"

#include "tracker/config.hpp"

#include <algorithm>
#include <vector>

namespace stairs {

std::optional<double> riser_overhang_m(const Plane& riser, const Eigen::Isometry3d& to_model, double nosing_z_m,
                                       const OverhangConfig& c) {
  if (riser.points.empty()) return std::nullopt;
  std::vector<Eigen::Vector2d> xz;
  xz.reserve(riser.points.size());
  double z_lo = nosing_z_m, z_hi = -1e9;
  for (const auto& p : riser.points) {
    const Eigen::Vector3d q = to_model * p.cast<double>();
    xz.emplace_back(q.x(), q.z());
    z_lo = std::min(z_lo, q.z());
    z_hi = std::max(z_hi, q.z());
  }
  // The slab is in view only when the plane reaches the nosing's height.
  if (z_hi < nosing_z_m - c.top_tolerance_m) return std::nullopt;
  const double h = nosing_z_m - z_lo;
  if (h < c.min_height_m) return std::nullopt;
  std::vector<double> top, face;
  for (const auto& q : xz) {
    const double f = (q.y() - z_lo) / h;  // 0 at the lowest point seen, 1 at the nosing
    if (f >= 1 - c.top_band_fraction) top.push_back(q.x());
    else if (f >= c.face_band_from && f <= c.face_band_to) face.push_back(q.x());
  }
  if (static_cast<int>(top.size()) < c.min_points || static_cast<int>(face.size()) < c.min_points) return std::nullopt;
  return median(face) - median(top);
}

double flight_overhang_m(const StairMap& map, const OverhangConfig& c) {
  std::vector<double> v;
  for (const MapStep& s : map.steps)
    if (s.overhang_m.known()) v.push_back(s.overhang_m.value);
  if (static_cast<int>(v.size()) < c.min_steps) return 0.0;
  return std::clamp(median(v), 0.0, c.max_m);
}

}  // namespace stairs
