#include "tracker/prior_links.hpp"

#include "tracker/config.hpp"

#include <algorithm>
#include <cmath>

namespace stairs {

void open_prior_links(StairMap& map) {
  // The steps this merge inserted: seen once, by the last merge.
  const auto inserted = [&](size_t k) {
    return map.steps[k].confirmations == 1 && map.steps[k].last_merge == map.merges;
  };
  for (size_t k = 1; k < map.steps.size(); ++k)
    if (inserted(k) != inserted(k - 1)) map.steps[k].prior_link = true;
}

std::optional<LinkClosure> measure_prior_link(const StairMap& map, const std::vector<ObservedStep>& observed,
                                              const MergeConfig& c, const StairPriorConfig& stair) {
  // The first open link: the part before it is the model's first step's, which the model's frame
  // stands on (../shared/DESIGN.md); a part between two open links is off by its own prior's error.
  size_t from = 1;
  while (from < map.steps.size() && !map.steps[from].prior_link) ++from;
  if (from >= map.steps.size()) return std::nullopt;
  size_t to = from + 1;
  while (to < map.steps.size() && !map.steps[to].prior_link) ++to;
  const std::vector<int> match = match_steps(map, observed, c, stair);
  std::vector<double> before_x, before_z, beyond_x, beyond_z;
  for (size_t i = 0; i < observed.size(); ++i) {
    if (match[i] < 0) continue;
    const size_t k = static_cast<size_t>(match[i]);
    const MapStep& m = map.steps[k];
    // Reconstructed steps were placed between seen ones, measured by neither part.
    if (m.reconstructed || k >= to) continue;
    (k < from ? before_x : beyond_x).push_back(observed[i].x() - m.x());
    (k < from ? before_z : beyond_z).push_back(observed[i].z() - m.z());
  }
  if (before_x.empty() || beyond_x.empty()) return std::nullopt;
  const Eigen::Vector2d shift(median(beyond_x) - median(before_x), median(beyond_z) - median(before_z));
  if (std::abs(shift.x()) > c.link_shift_fraction * typical_tread_m(map, stair) ||
      std::abs(shift.y()) > c.link_shift_fraction * typical_riser_m(map, stair))
    return std::nullopt;
  return LinkClosure{from, shift};
}

void close_prior_link(StairMap& map, const LinkClosure& closure) {
  const double dx = closure.shift_m.x(), dz = closure.shift_m.y();
  const auto move_points = [&](std::vector<Eigen::Vector3f>& points) {
    for (Eigen::Vector3f& p : points) {
      p.x() += static_cast<float>(dx);
      p.z() += static_cast<float>(dz);
    }
  };
  const double boundary_x = map.steps[closure.from - 1].x();
  for (size_t k = closure.from; k < map.steps.size(); ++k) {
    MapStep& s = map.steps[k];
    s.riser_x_m.value += dx;
    s.nosing_x_m.value += dx;
    s.tread_z_m.value += dz;
    s.edge_z_m.value += dz;
    if (s.tread_far_x_m > -1e8) s.tread_far_x_m += dx;
    move_points(s.riser_points);
    move_points(s.tread_points);
  }
  map.steps[closure.from].prior_link = false;
  if (map.end_wall_x_m.known() && map.end_wall_x_m.value > boundary_x) map.end_wall_x_m.value += dx;
}

}  // namespace stairs
