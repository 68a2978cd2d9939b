// Stage 5c: step edges from the normal image (thesis 3.4.1, Algorithm 6).
// Where a riser meets a tread the surface turns by about 90 deg: drawn as
// colours, the normals show every step edge as a colour edge, the nosings
// (convex) and the riser feet (concave) alike. Going down the risers are
// hidden and the treads share one colour; edges_depth_jumps covers that case.
#pragma once

#include "common/types.hpp"
#include "perception/config.hpp"
#include "perception/normals.hpp"

#include <Eigen/Core>
#include <vector>

namespace stairs {

// Thesis 3.4.1: normal image -> blur -> Canny -> contours -> Hough; each line is the meet of the
// surfaces on its two sides, kept if they bend, it is level and across the stair axis; close lines
// merge (histogram). Pixel lengths in cfg are at 640 wide. Gravity-aligned frame, strongest first.
std::vector<Edge> normal_image_edges(const NormalGrid& grid, const Eigen::Matrix3f& gravity, float yaw_rad,
                                     const NormalImageEdgesConfig& cfg, int grid_cell_px_640, float min_length_m);

}  // namespace stairs
