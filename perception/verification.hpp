// Stage 8: verification. A staircase hypothesis from the grammar (stage 6)
// fits DIN numbers; furniture can too (a chair seat and a table top make a
// two-step "flight"). A hypothesis is kept only where the depth image shows
// the evidence a real flight leaves, and where the evidence is missing the
// steps it cannot vouch for are dropped: unknown beats wrong. Not in the
// thesis (its grammar, 4.3, is the whole test); our own stage.
#pragma once

#include "common/types.hpp"
#include "perception/config.hpp"
#include "perception/normals.hpp"
#include "perception/plane_geometry.hpp"

#include <string>
#include <vector>

namespace stairs {


// Outcome: the steps kept (a nearest-first prefix of the input; fewer than the
// pipeline's min_steps = no staircase) and, when steps were dropped, why.
struct Verdict {
  size_t kept = 0;
  std::string reason;  // empty when every step passed
};

// Probes the grid (optical frame; `gravity` = optical -> gravity-aligned) for
// each step's evidence, nearest first; a step that fails a check is dropped
// with every step beyond it. Widths and nosing lines are in the stair-aligned
// frame of `planes`. Sets kStepWidthPartial on steps whose width is a lower
// bound. `max_rise_m`: DIN's highest rise with its tolerance (the grammar's),
// above which a measured rise is no step.
Verdict verify(const NormalGrid& grid, const Intrinsics& K, const Eigen::Matrix3f& gravity, const PlaneSet& planes,
               Direction direction, std::vector<Step>& steps, const VerificationConfig& cfg, float max_rise_m);

}  // namespace stairs
