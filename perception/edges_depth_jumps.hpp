// Stage 5b: step edges from depth jumps (thesis 3.4.2). Looking down a flight
// each nosing hides the near part of the tread below it, so the image jumps
// in depth along every nosing. Far treads show as strips too thin for planes,
// but their nosings still show as jumps.
#pragma once

#include "perception/normals.hpp"

#include <Eigen/Core>
#include <vector>

namespace stairs {

// A convex step edge in the stair-aligned frame of plane_geometry (s along
// the stair axis, t lateral, z up; m) with its end points in the
// gravity-aligned camera frame.
struct JumpEdge {
  float s = 0, z = 0, t_min = 0, t_max = 0;
  Edge edge;  // the observation's edge (source DepthJump, type Convex)
};

// Near sides of the jumps between vertically neighbouring cells (the farther
// cell above it in the image), rotated by `gravity` (optical -> gravity-aligned)
// and grouped by height; RANSAC fits a line to each group. Lines that are not
// horizontal, not across the stair axis (`yaw_rad`) or shorter than
// `min_length_m` (the narrowest step) are dropped. Sorted by height, highest first.
std::vector<JumpEdge> depth_jump_edges(const NormalGrid& grid, const Eigen::Matrix3f& gravity, float yaw_rad,
                                       const DepthJumpEdgesConfig& cfg, float min_length_m);

}  // namespace stairs
