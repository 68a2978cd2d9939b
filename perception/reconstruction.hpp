// Stage 7: occlusion reconstruction (thesis section 4.5). Going down the
// risers are hidden: each is rebuilt between the nosing and the tread below.
// Tread depths are corrected from nosing to nosing (the visible part of a
// tread is cut by the step in front of it); a deeper tread is a landing.
#pragma once

#include "perception/steps.hpp"

namespace stairs {

void reconstruct(PlaneSet& planes, const StairChain& chain, std::vector<Step>& steps, const StairConfig& cfg);

}  // namespace stairs
