// Stage 6a: tread levels from the planes and steps from a chain of levels.
#pragma once

#include "perception/edges_depth_jumps.hpp"
#include "perception/plane_geometry.hpp"

#include <vector>

namespace stairs {

// A horizontal plane as a stair level (stair-aligned extents, m).
struct Level {
  int plane = -1;
  float z = 0, s_min = 0, s_max = 0, t_min = 0, t_max = 0;
  bool far_edge = false;    // a depth-jump edge ends it (its nosing, seen from above)
  float edge_s = 0;         // where that edge lies along the axis (valid with far_edge)
  bool riser_top = false;   // the top of a riser facing the camera (a tread seen edge-on)
  // How far its plane's heights (trimmed percentiles) reach below and above z;
  // 0 for an edge's level.
  float reach_below_m = 0, reach_above_m = 0;
  Strips strips{};           // its plane's (empty for a riser's top or an edge's level)
};

// Where level `a` ends along the stair under level `b`, the next one up: its whole extent's end,
// unless that runs on past b's start by more than `run_on_m`; then its end across b's width.
float end_under(const Level& a, const Level& b, float run_on_m);
// Where level `b` starts along the stair beyond level `a`, the one above it going down: its whole
// extent's start, unless that reaches back before a's end by more than `run_on_m`; then its start
// across a's width (the floor beside an open-sided flight reaches back under its top).
float start_beyond(const Level& b, const Level& a, float run_on_m);

// Levels of the tread planes, of the tops of risers and of the depth-jump
// edges whose tread is not segmented, lowest first; planes narrower than
// min_step_width_m are not steps.
std::vector<Level> tread_levels(const PlaneSet& planes, const std::vector<JumpEdge>& edges,
                                const StairConfig& cfg);

// A staircase hypothesis: a chain of levels in walking order (`Up`: floor
// first then each higher tread; `Down`: the level the camera looks from first).
struct StairChain {
  Direction direction = Direction::None;
  std::vector<Level> levels;
  double deviation = 0;  // summed relative DIN deviation, lower is better
  int landings = 0;      // treads deeper than landing_min_depth_m with levels beyond them
  int steps() const { return levels.empty() ? 0 : static_cast<int>(levels.size()) - 1; }
};

// Steps of a chain, nearest first, with visible tread extents (reconstruction
// corrects them) and the matching segmented riser plane when there is one.
std::vector<Step> steps_from_chain(const PlaneSet& planes, const StairChain& chain, const StairConfig& cfg);

}  // namespace stairs
