#include "tracker/stair_map.hpp"

#include "tracker/config.hpp"

#include <algorithm>
#include <cmath>

namespace stairs {

double typical_riser_m(const StairMap& map, const StairPriorConfig& c) {
  std::vector<double> r;
  for (const auto& s : map.steps)
    if (s.riser_height_m.known()) r.push_back(s.riser_height_m.value);
  for (size_t i = 1; i < map.steps.size(); ++i) {
    const double dz = map.steps[i].z() - map.steps[i - 1].z();
    if (std::abs(dz - c.default_riser_m) < c.riser_bracket_fraction * c.default_riser_m) r.push_back(dz);
  }
  return r.empty() ? c.default_riser_m : median(r);
}

double typical_tread_m(const StairMap& map, const StairPriorConfig& c) {
  std::vector<double> t;
  const double riser = typical_riser_m(map, c);
  for (size_t i = 1; i < map.steps.size(); ++i) {
    const double dz = map.steps[i].z() - map.steps[i - 1].z();
    const double dx = map.steps[i].x() - map.steps[i - 1].x();
    if (std::abs(dz - riser) < c.typical_riser_fraction * riser && dx < c.landing_min_depth_m) t.push_back(dx);
  }
  return t.empty() ? c.default_tread_m : median(t);
}

Eigen::Vector3d typical_step_m(const StairMap& map, const StairPriorConfig& c) {
  return Eigen::Vector3d(typical_tread_m(map, c), 0.0, typical_riser_m(map, c));
}

double floor_z_m(const StairMap& map, const StairPriorConfig& c) {
  const MapStep& first = map.steps.front();
  const double riser = first.riser_height_m.known() ? first.riser_height_m.value : typical_riser_m(map, c);
  return first.z() - riser;
}

double surface_z_m(const StairMap& map, double x_m, const StairPriorConfig& c) {
  double z = floor_z_m(map, c);
  for (const MapStep& s : map.steps)
    if (s.x() <= x_m) z = s.z();
  return z;
}

double mean_surface_z_m(const StairMap& map, double x_m, const StairPriorConfig& c) {
  // Exact mean of the piecewise-constant surface over [x - half, x + half].
  const double half = 0.5 * typical_tread_m(map, c);
  double at = x_m - half, z = surface_z_m(map, at, c), sum = 0.0;
  for (const MapStep& s : map.steps)
    if (s.x() > at && s.x() < x_m + half) {
      sum += (s.x() - at) * z;
      at = s.x();
      z = s.z();
    }
  sum += (x_m + half - at) * z;
  return sum / (2.0 * half);
}

bool reaches_a_flight_end(const StairMap& map, double a_m, double b_m, const StairPriorConfig& c) {
  if (map.steps.empty()) return false;
  const double half = 0.5 * typical_tread_m(map, c);
  const double lo = std::min(a_m, b_m) - half, hi = std::max(a_m, b_m) + half;
  auto near = [&](const MapStep& s) { return s.x() >= lo && s.x() <= hi; };
  if (near(map.steps.front()) || near(map.steps.back())) return true;
  for (size_t i = 0; i + 1 < map.steps.size(); ++i)
    if (map.steps[i + 1].x() - map.steps[i].x() > c.landing_min_depth_m &&
        (near(map.steps[i]) || near(map.steps[i + 1])))
      return true;
  return false;
}

}  // namespace stairs
