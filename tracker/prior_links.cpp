#include "tracker/prior_links.hpp"

#include "tracker/config.hpp"

#include <algorithm>
#include <cmath>

namespace stairs {

namespace {

// Whether the last merge inserted step k: seen once, by it.
bool inserted(const StairMap& map, size_t k) {
  return map.steps[k].confirmations == 1 && map.steps[k].last_merge == map.merges;
}

}  // namespace

void open_prior_links(StairMap& map, double uncertainty_m) {
  for (size_t k = 1; k < map.steps.size(); ++k)
    if (inserted(map, k) != inserted(map, k - 1))
      map.steps[k].prior_link_m = std::max(map.steps[k].prior_link_m, uncertainty_m);
}

void extend_prior_links(StairMap& map, double registered_on_x_m) {
  for (size_t k = 2; k < map.steps.size(); ++k) {
    if (map.steps[k].prior_link_m <= 0.0) continue;
    size_t at = k;
    while (at > 1 && inserted(map, at - 1) && registered_on_x_m > map.steps[at - 1].x()) --at;
    std::swap(map.steps[at].prior_link_m, map.steps[k].prior_link_m);
  }
}

bool any_open_prior_link(const StairMap& map) {
  return std::any_of(map.steps.begin(), map.steps.end(), [](const MapStep& s) { return s.prior_link_m > 0.0; });
}

std::vector<double> prior_link_uncertainties_m(const StairMap& map, double registered_on_x_m) {
  if (!any_open_prior_link(map)) return {};
  size_t on = 0;
  for (size_t k = 1; k < map.steps.size(); ++k)
    if (std::abs(map.steps[k].x() - registered_on_x_m) < std::abs(map.steps[on].x() - registered_on_x_m)) on = k;
  // Links summed from the first step; between two steps, the difference of their sums.
  std::vector<double> sum(map.steps.size(), 0.0);
  for (size_t k = 1; k < map.steps.size(); ++k) sum[k] = sum[k - 1] + map.steps[k].prior_link_m;
  for (double& s : sum) s = std::abs(s - sum[on]);
  return sum;
}

std::optional<LinkClosure> measure_prior_link(const StairMap& map, const std::vector<ObservedStep>& observed,
                                              const MergeConfig& c, const StairPriorConfig& stair, int min_steps) {
  // The first open link: the part before it is the model's first step's, which the model's frame
  // stands on (../shared/DESIGN.md); a part between two open links is off by its own prior's error.
  size_t from = 1;
  while (from < map.steps.size() && map.steps[from].prior_link_m <= 0.0) ++from;
  if (from >= map.steps.size()) return std::nullopt;
  size_t to = from + 1;
  while (to < map.steps.size() && map.steps[to].prior_link_m <= 0.0) ++to;
  const std::vector<int> match = match_steps(map, observed, c, stair);
  std::vector<double> before, beyond;
  for (size_t i = 0; i < observed.size(); ++i) {
    if (match[i] < 0) continue;
    const size_t k = static_cast<size_t>(match[i]);
    const MapStep& m = map.steps[k];
    // Reconstructed steps were placed between seen ones, measured by neither part.
    if (m.reconstructed || k >= to) continue;
    (k < from ? before : beyond).push_back(observed[i].x() - m.x());
  }
  if (static_cast<int>(before.size()) < min_steps || static_cast<int>(beyond.size()) < min_steps) return std::nullopt;
  const double shift = median(beyond) - median(before);
  if (std::abs(shift) > c.link_shift_fraction * typical_tread_m(map, stair)) return std::nullopt;
  return LinkClosure{from, shift};
}

void close_prior_link(StairMap& map, const LinkClosure& closure) {
  const double dx = closure.shift_x_m;
  const double boundary_x = map.steps[closure.from - 1].x();
  for (size_t k = closure.from; k < map.steps.size(); ++k) {
    MapStep& s = map.steps[k];
    s.riser_x_m.value += dx;
    s.nosing_x_m.value += dx;
    if (s.tread_far_x_m > -1e8) s.tread_far_x_m += dx;
    for (auto* points : {&s.riser_points, &s.tread_points})
      for (Eigen::Vector3f& p : *points) p.x() += static_cast<float>(dx);
  }
  map.steps[closure.from].prior_link_m = 0.0;
  if (map.end_wall_x_m.known() && map.end_wall_x_m.value > boundary_x) map.end_wall_x_m.value += dx;
}

}  // namespace stairs
