#include "perception/camera_height.hpp"

#include <algorithm>
#include <cmath>

namespace stairs {

namespace {

// The longest run a tread of this flight may have: its longest measured one
// (a landing's depth and a run cut by the view are no runs), else the
// plausible maximum, plus the regularity tolerance.
double longest_run_m(const std::vector<Step>& steps, float tread_max_m, float run_tolerance_m) {
  double run = 0.0;
  for (const Step& s : steps)
    if (s.tread_depth_m && !s.landing && !(s.inferred & kStepTreadPartial)) run = std::max(run, *s.tread_depth_m);
  return (run > 0.0 ? run : tread_max_m) + run_tolerance_m;
}

}  // namespace

std::optional<double> camera_height(const PlaneSet& ps, const std::vector<Step>& steps, Direction direction,
                                    const Intrinsics& K, double pitch_deg, const CameraHeightConfig& cfg,
                                    const StairConfig& stair, float run_tolerance_m) {
  const double below_rad = -pitch_deg * M_PI / 180.0 + std::atan((K.height - 1 - K.cy) / K.fy);
  if (below_rad <= 0) return std::nullopt;
  if (below_rad >= M_PI / 2) {
    // The point straight beneath is in view: the lowest surface spanning it.
    const PlaneExtent* beneath = nullptr;
    for (size_t i = 0; i < ps.planes.size(); ++i) {
      const PlaneExtent& e = ps.extents[i];
      if (ps.planes[i].kind == PlaneKind::Tread && e.z_mean < 0 && e.s_min <= cfg.view_edge_margin_m &&
          e.s_max >= 0 && (!beneath || e.z_mean < beneath->z_mean))
        beneath = &e;
    }
    return beneath ? std::optional<double>(-beneath->z_mean) : std::nullopt;
  }
  if (steps.empty() || direction == Direction::None) return std::nullopt;
  const Step& first = steps.front();
  const double edge_s = ps.axial(first.nosing_m);
  if (edge_s <= 0) return std::nullopt;  // over the flight: its treads' fronts are out of view
  double level_z = first.nosing_m.z();   // going down: the top landing
  if (direction == Direction::Up) {
    if (!first.riser_height_m || (first.inferred & kStepRiserInferred)) return std::nullopt;
    level_z -= *first.riser_height_m;  // the floor at the first riser's foot
  }
  // The lowest surface reaching the image's lowest row.
  const PlaneExtent* lowest = nullptr;
  for (size_t i = 0; i < ps.planes.size(); ++i) {
    const PlaneExtent& e = ps.extents[i];
    if (ps.planes[i].kind != PlaneKind::Tread || e.z_mean >= 0) continue;
    const double view_edge_m = below_rad >= M_PI / 2 ? 0.0 : -e.z_mean / std::tan(below_rad);
    if (e.s_min < view_edge_m * (1 + cfg.view_edge_tolerance) + cfg.view_edge_margin_m &&
        (!lowest || e.z_mean < lowest->z_mean))
      lowest = &e;
  }
  if (!lowest || std::abs(lowest->z_mean - level_z) > stair.same_level_m) return std::nullopt;
  if (edge_s - lowest->s_min <= longest_run_m(steps, stair.tread_max_m, run_tolerance_m)) return std::nullopt;
  return -static_cast<double>(lowest->z_mean);
}

}  // namespace stairs
