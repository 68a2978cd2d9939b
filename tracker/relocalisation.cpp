#include "tracker/relocalisation.hpp"

#include "tracker/config.hpp"

namespace stairs {

Registration relocalise(const RegistrationInput& in, const StairMap& map, const Pose4& prior,
                        const RelocalisationConfig& c, const RegistrationConfig& registration,
                        const StairPriorConfig& stair) {
  const Eigen::Vector3d step(typical_tread_m(map, stair), 0.0, typical_riser_m(map, stair));
  Registration best;
  for (int k = 0; k <= c.step_range; k = k > 0 ? -k : -k + 1) {
    Pose4 start = prior;
    start.t_m += k * step;
    const Registration r = register_to_map(in, map, start, registration, stair);
    // A shift must beat the prior clearly: min_gain more agreeing points.
    const double margin = k == 0 ? 0.0 : c.min_gain * best.inliers + 1;
    if (k == 0 || r.inliers > best.inliers + margin) best = r;
    if (c.step_range == 0) break;
  }
  return best;
}

}  // namespace stairs
