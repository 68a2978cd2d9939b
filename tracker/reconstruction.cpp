#include "tracker/reconstruction.hpp"

#include "tracker/config.hpp"

#include <cmath>

namespace stairs {

int reconstruct_occluded_steps(StairMap& map, const ModelReconstructionConfig& c, const StairPriorConfig& stair,
                               int min_confirmations, int max_model_steps) {
  const double riser = typical_riser_m(map, stair);
  const double tread = typical_tread_m(map, stair);
  int filled = 0;
  for (size_t i = 1; i < map.steps.size(); ++i) {
    const MapStep& a = map.steps[i - 1];
    const MapStep& b = map.steps[i];
    if (a.confirmations < min_confirmations || b.confirmations < min_confirmations) continue;
    const double dz = b.z() - a.z(), dx = b.x() - a.x();
    const int n = static_cast<int>(std::lround(dz / riser));
    if (n < 2 || n - 1 > c.max_gap_steps ||
        static_cast<int>(map.steps.size()) + n - 1 > max_model_steps)
      continue;
    if (std::abs(dz - n * riser) > c.tolerance * riser ||
        std::abs(dx - n * tread) > c.tolerance * n * tread)
      continue;
    std::vector<MapStep> hidden;
    for (int k = 1; k < n; ++k) {
      MapStep s;
      const double f = static_cast<double>(k) / n;
      s.nosing_x_m.add(a.x() + f * dx, 1);
      s.edge_z_m.add(a.z() + f * dz, 1);  // interpolated: a seen tread plane overrides it
      if (a.y_min_m.known()) s.y_min_m.add(a.y_min_m.value, 1);
      if (a.y_max_m.known()) s.y_max_m.add(a.y_max_m.value, 1);
      s.reconstructed = true;
      hidden.push_back(std::move(s));
    }
    map.steps.insert(map.steps.begin() + i, hidden.begin(), hidden.end());
    i += hidden.size();
    filled += n - 1;
  }
  return filled;
}

}  // namespace stairs
