#include "tracker/relocalisation.hpp"

#include "tracker/config.hpp"

namespace stairs {

Registration relocalise(const RegistrationInput& in, const StairMap& map, const Pose4& prior, const TrackerConfig& c) {
  const Eigen::Vector3d step(typical_tread_m(map, c), 0.0, typical_riser_m(map, c));
  Registration best;
  for (int k = 0; k <= c.relocalise_step_range; k = k > 0 ? -k : -k + 1) {
    Pose4 start = prior;
    start.t_m += k * step;
    const Registration r = register_to_map(in, map, start, c);
    // A shift must beat the prior clearly: relocalise_min_gain more agreeing points.
    const double margin = k == 0 ? 0.0 : c.relocalise_min_gain * best.inliers + 1;
    if (k == 0 || r.inliers > best.inliers + margin) best = r;
    if (c.relocalise_step_range == 0) break;
  }
  return best;
}

}  // namespace stairs
