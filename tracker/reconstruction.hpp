// Occlusion reconstruction on the model (thesis 4.5, applied to the fused
// model): where two seen steps are n whole steps apart in both height and depth,
// the n-1 steps hidden between them are filled in. A later observation of such
// a step confirms it like any other.
#pragma once

#include "tracker/stair_map.hpp"

namespace stairs {

struct ModelReconstructionConfig;
struct StairPriorConfig;

// Returns the number of steps filled in.
int reconstruct_occluded_steps(StairMap& map, const ModelReconstructionConfig& c, const StairPriorConfig& stair,
                               int min_confirmations, int max_model_steps);

}  // namespace stairs
