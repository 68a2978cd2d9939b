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

// The grid's normals rotated by `gravity` (optical -> gravity-aligned) as a
// colour image at cell resolution -> Gaussian blur -> Canny -> contours
// spanning at least normal_edge_min_contour_px -> probabilistic Hough lines.
// Each line becomes the intersection of the surfaces on its two sides, along
// the cells under it; it is kept when the surfaces bend by at least
// cfg.min_bend_deg, it is horizontal and across the stair axis (`yaw_rad`)
// and within cfg.max_range_m. Lines of one type close in direction, distance
// and height merge (histogram); merged lines shorter than `min_length_m` (the
// narrowest step) are dropped. Pixel lengths in cfg are at 640 wide, in cells
// of `grid_cell_px_640`. Edges (source NormalImage, Convex or
// Concave) are in the gravity-aligned camera frame, strongest first.
std::vector<Edge> normal_image_edges(const NormalGrid& grid, const Eigen::Matrix3f& gravity, float yaw_rad,
                                     const NormalImageEdgesConfig& cfg, int grid_cell_px_640, float min_length_m);

}  // namespace stairs
