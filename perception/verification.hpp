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

// Probes the grid for each step's evidence, nearest first; a failing step is dropped with all
// beyond it, and a width that is only a lower bound is flagged partial. `max_rise_m`: the grammar's.
Verdict verify(const NormalGrid& grid, const Intrinsics& K, const Eigen::Matrix3f& gravity, const PlaneSet& planes,
               Direction direction, std::vector<Step>& steps, const VerificationConfig& cfg, float max_rise_m);

}  // namespace stairs
