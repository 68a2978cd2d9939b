// Stage 5b: step edges from depth jumps (thesis 3.4.2). Looking down a flight
// each nosing hides the near part of the tread below it, so the image jumps
// in depth along every nosing. Far treads show as strips too thin for planes,
// but their nosings still show as jumps.
#pragma once

#include "perception/normals.hpp"

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace stairs {

// A convex step edge in the stair-aligned frame of plane_geometry (s along
// the stair axis, t lateral, z up; m) with its end points in the
// gravity-aligned camera frame.
struct JumpEdge {
  float s = 0, z = 0, t_min = 0, t_max = 0;  // of the near cells' mean points
  float nosing_s = 0;  // the edge itself along the axis: the near cells placed at the jump's pixel row
  Eigen::Vector2f across = Eigen::Vector2f::UnitY();  // the fitted line's horizontal direction (unit, either sign)
  Edge edge;  // the observation's edge (source DepthJump, type Convex)
};

// Nosings seen from above (thesis 3.4): near sides of depth jumps, grouped by height, a RANSAC line
// per group; kept if horizontal, across the stair axis and at least `min_length_m`; nosing_s from the
// jump's pixel rows in `frame` (the depth the grid was made of). Highest first.
std::vector<JumpEdge> depth_jump_edges(const NormalGrid& grid, const DepthImage& frame, const Eigen::Matrix3f& gravity,
                                       float yaw_rad, const DepthJumpEdgesConfig& cfg, float min_length_m);

struct EdgeAxis {
  float yaw_rad = 0;  // from camera forward
  int heights = 0;    // distinct heights its lines lie at (more than 2 height_gap_m apart)
};

// The stair axis perpendicular to the edges' lines, their support weighting the doubled angles (a
// line's direction has no sign), over the lines within cluster_deg of the best-supported direction;
// none without edges. Looking down a flight its risers are hidden and the nosings are the only lines
// across it.
std::optional<EdgeAxis> axis_from_edges(const std::vector<JumpEdge>& edges, float cluster_deg, float height_gap_m);

}  // namespace stairs
