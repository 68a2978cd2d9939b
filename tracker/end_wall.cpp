#include "tracker/end_wall.hpp"

#include "tracker/config.hpp"
#include "tracker/registration.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace stairs {

namespace {

void forget(StairMap& map) {
  map.end_wall_x_m = map.end_wall_uncertainty_m = RunningMean{};
  map.end_wall_confirmed = false;
}

}  // namespace

void note_end_wall(StairMap& map, const Observation& obs, const Pose4& pose, double pose_uncertainty_m,
                   const EndWallConfig& c, const StairPriorConfig& stair, int max_average_weight,
                   int min_observations) {
  if (map.empty()) return;
  const MapStep& top = map.steps.back();
  const double min_x = top.x() + c.min_run_fraction * typical_tread_m(map, stair);
  if (map.end_wall_x_m.known() && map.end_wall_x_m.value < min_x) forget(map);
  const std::vector<bool> owned = planes_owned_by_steps(obs);
  const Eigen::Isometry3d T = pose.isometry();
  const double max_foot_dz = c.max_foot_offset_rise_fraction * typical_riser_m(map, stair);
  const double min_facing = std::cos(c.max_normal_deg * M_PI / 180.0);
  for (size_t k = 0; k < obs.planes.size(); ++k) {
    const Plane& p = obs.planes[k];
    if (owned[k] || p.kind != PlaneKind::Riser || p.points.empty() || p.length_m < c.min_width_m) continue;
    // Facing down the flight: towards -x, where a climber comes from.
    if ((pose.rotation() * p.normal.cast<double>()).x() > -min_facing) continue;
    std::vector<double> xs;
    double z_lo = 1e9;
    for (const auto& q : p.points) {
      const Eigen::Vector3d w = T * q.cast<double>();
      xs.push_back(w.x());
      z_lo = std::min(z_lo, w.z());
    }
    const double x = median(xs);
    if (x < min_x || z_lo < top.z() - max_foot_dz) continue;
    map.end_wall_x_m.add(x, max_average_weight);
    map.end_wall_uncertainty_m.add(pose_uncertainty_m, max_average_weight);
    if (map.end_wall_x_m.count >= min_observations) map.end_wall_confirmed = true;
    return;
  }
}

std::optional<double> end_wall_x_m(const StairMap& map) {
  if (!map.end_wall_confirmed || map.empty() || map.end_wall_x_m.value <= map.steps.back().x()) return std::nullopt;
  return map.end_wall_x_m.value;
}

}  // namespace stairs
