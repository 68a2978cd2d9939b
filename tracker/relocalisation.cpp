#include "tracker/relocalisation.hpp"

#include "tracker/config.hpp"

namespace stairs {

Registration relocalise(const RegistrationInput& in, const StairMap& map, const Pose4& prior,
                        const RelocalisationConfig& c, const RegistrationConfig& registration,
                        const StairPriorConfig& stair, double max_shift_m) {
  // Starts half a step apart: ICP reaches icp_max_tread_fraction (0.4) of a
  // tread from its start, so whole-step starts leave offsets near half a step
  // (a robot tipping over a nosing jumps that far in one frame) out of reach.
  const Eigen::Vector3d half_step = 0.5 * Eigen::Vector3d(typical_tread_m(map, stair), 0.0, typical_riser_m(map, stair));
  Registration best;
  for (int k = 0; k <= 2 * c.step_range; k = k > 0 ? -k : -k + 1) {
    // Half a step either way is always tried (a robot tipping over a nosing jumps that far in a
    // frame); a start farther off than the prior may be is no hypothesis: a walker's first frame
    // after 0.4 s without steps, the mid landing's edge and the next flight's first nosing in view,
    // fitted best a whole step back (the new flight's points then lay on the model) and the tracker
    // re-seeded the second flight onto the first.
    if (std::abs(k) > 1 && std::abs(k) * half_step.x() > max_shift_m) continue;
    Pose4 start = prior;
    start.t_m += k * half_step;
    const Registration r = register_to_map(in, map, start, registration, stair);
    // A shift must beat the prior clearly: min_gain more agreeing points. A
    // nosing counts as many points as in the ICP: going down, the nosings are
    // all that fixes x (treads agree wherever along them the camera is).
    auto agreeing = [&](const Registration& g) { return g.inliers + registration.nosing_weight_points * g.nosing_inliers; };
    const double margin = k == 0 ? 0.0 : c.min_gain * agreeing(best) + 1;
    if (k == 0 || agreeing(r) > agreeing(best) + margin) best = r;
    if (c.step_range == 0) break;
  }
  return best;
}

}  // namespace stairs
