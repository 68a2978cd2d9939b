// Stage 6b: the stair grammar (thesis Figure 4.3): each level's successor is
// the next plausible step (DIN 18065 with tolerance); a tread deeper than
// landing_min_depth_m is a landing. Several chains are built; the best is kept.
#pragma once

#include "perception/steps.hpp"

namespace stairs {

// True when riser, tread and 2R+T lie within the DIN bounds widened by the tolerance.
bool din_riser_ok(double riser_m, const StairConfig& cfg);
bool din_tread_ok(double tread_m, const StairConfig& cfg);
bool din_rule_ok(double riser_m, double tread_m, const StairConfig& cfg);

// The best chain over both directions and every start level; direction None
// when no chain has a step (the pipeline asks cfg.min_steps after reconstruction).
StairChain best_chain(const std::vector<Level>& levels, const StairConfig& cfg);

}  // namespace stairs
