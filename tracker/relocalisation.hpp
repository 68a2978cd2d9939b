// Re-localisation against the model after a gap, or when a registration's
// nosings and risers all disagree: a periodic stair is ambiguous by whole
// steps, so registration is tried from the motion prior shifted by -k..k steps
// in half steps and the shift that agrees best with the model wins (ties go to
// the smallest shift, i.e. to the motion prior and its step-count bookkeeping).
#pragma once

#include "tracker/registration.hpp"

namespace stairs {

struct RelocalisationConfig;

Registration relocalise(const RegistrationInput& in, const StairMap& map, const Pose4& prior,
                        const RelocalisationConfig& c, const RegistrationConfig& registration,
                        const StairPriorConfig& stair);

}  // namespace stairs
