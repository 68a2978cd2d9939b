// Re-localisation against the model after a gap, or when a registration's
// nosings and risers all disagree: a periodic stair is ambiguous by whole
// steps, so registration is tried from the motion prior shifted by -k..k steps
// in half steps (along the stair's slope, and level where the prior is not stale:
// a camera swinging on a robot; an infinite `max_shift_m` is a lost stair's stale prior) and the shift that agrees best with the model wins (ties go to
// the smallest shift, i.e. to the motion prior and its step-count bookkeeping). Shifts beyond half a
// step and farther than `max_shift_m` along the stair (how far off the prior may be, plus what ICP
// reaches from a start) are not tried: the prior rules them out.
#pragma once

#include "tracker/registration.hpp"

namespace stairs {

struct RelocalisationConfig;

// `ambiguous` (when given): another whole-step shift fits about as well as the one returned.
Registration relocalise(const RegistrationInput& in, const StairMap& map, const Pose4& prior,
                        const RelocalisationConfig& c, const RegistrationConfig& registration,
                        const StairPriorConfig& stair, double max_shift_m, bool* ambiguous = nullptr);

}  // namespace stairs
