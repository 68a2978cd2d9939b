#include "tracker/relocalisation.hpp"

#include "tracker/config.hpp"

#include <cmath>
#include <vector>

namespace stairs {

Registration relocalise(const RegistrationInput& in, const StairMap& map, const Pose4& prior,
                        const RelocalisationConfig& c, const RegistrationConfig& registration,
                        const StairPriorConfig& stair, double max_shift_m, bool* ambiguous) {
  // Starts half a step apart: ICP reaches icp_max_tread_fraction (0.4) of a
  // tread from its start, so whole-step starts leave offsets near half a step
  // (a robot tipping over a nosing jumps that far in one frame) out of reach.
  const Eigen::Vector3d half_step = 0.5 * typical_step_m(map, stair);
  // A nosing counts as many points as in the ICP: going down, the nosings are all that fixes x
  // (treads agree wherever along them the camera is).
  auto agreeing = [&](const Registration& g) { return agreeing_points(g, registration); };
  // `a` beats `b` clearly: min_gain more agreeing points than b's.
  auto clearly_better = [&](const Registration& a, const Registration& b) {
    return agreeing(a) > agreeing(b) + c.min_gain * agreeing(b) + 1;
  };
  auto off_prior_m = [&](const Registration& g) { return (g.pose.t_m - prior.t_m).norm(); };
  Registration best = register_to_map(in, map, prior, registration, stair);
  std::vector<Registration> tried{best};
  for (int k = 1; k <= 2 * c.step_range; ++k) {
    // Half a step either way is always tried (a robot tipping over a nosing jumps that far in a
    // frame); a start farther off than the prior may be is no hypothesis: a walker's first frame
    // after 0.4 s without steps, the mid landing's edge and the next flight's first nosing in view,
    // fitted best a whole step back (the new flight's points then lay on the model) and the tracker
    // re-seeded the second flight onto the first.
    if (k > 1 && k * half_step.x() > max_shift_m) break;
    // Along the stair's slope (a walker or a robot moving on along it), and, from a prior that is not
    // stale, along the stair at its height: a camera swinging on a robot's pitching body moves on or
    // back with little height change (a robot's camera 25 cm behind its prior at the same height was
    // fitted from no start on the slope: those a tread back start 10 cm below it, ICP took the tread
    // below there, and the one fit it found, a whole step up, looked unambiguous: a false step above
    // the flight). A lost stair's prior is stale in height too, and every shift is tried: level starts
    // there fitted a flight seen after a gap onto the other one on 3 risers and nosings.
    for (const double slope : {1.0, 0.0}) {
      if (slope == 0.0 && !std::isfinite(max_shift_m)) break;
      Registration pair[2];
      for (int side = 0; side < 2; ++side) {
        Pose4 start = prior;
        const double shift = side == 0 ? k : -k;
        start.t_m.x() += shift * half_step.x();
        start.t_m.z() += slope * shift * half_step.z();
        pair[side] = register_to_map(in, map, start, registration, stair);
        tried.push_back(pair[side]);
      }
      // The same shift back and forth, neither clearly better: the one that ends nearer the prior (a
      // robot's camera on a 1.1 m mast, rocking 10 cm a frame over the nosings, was put a step back
      // by the start tried first, four frames in a row, and the tracker ran up the stair adding steps).
      const bool second = clearly_better(pair[1], pair[0]) ||
                          (!clearly_better(pair[0], pair[1]) && off_prior_m(pair[1]) < off_prior_m(pair[0]));
      const Registration& r = pair[second ? 1 : 0];
      // A shift must beat the prior (and the smaller shifts) clearly.
      if (clearly_better(r, best)) best = r;
    }
  }
  // Another whole-step shift (more than half a step from the winner) that the winner does not beat
  // clearly: the observation fits either, and the winner is the tie-break's.
  if (ambiguous) {
    *ambiguous = false;
    for (const Registration& r : tried)
      if ((r.pose.t_m - best.pose.t_m).norm() > half_step.norm() && !clearly_better(best, r)) *ambiguous = true;
  }
  return best;
}

}  // namespace stairs
