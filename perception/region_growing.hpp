// Stage 2: planar segments by region growing on the normal grid.
#pragma once

#include "perception/normals.hpp"

#include <vector>

namespace stairs {

struct Segment {
  std::vector<int> cells;  // grid indices
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero();  // m, optical frame
  Eigen::Vector3f normal = Eigen::Vector3f::UnitZ();   // least-squares, towards the camera
  float rms_m = 0.0f;                                  // point-to-plane
  // In-plane axes of the cells' spread (unit, optical frame) and the variance along each, m^2:
  // how well the normal's tilt towards each is known (a thin strip's, across it, poorly).
  Eigen::Vector3f axis[2] = {Eigen::Vector3f::UnitX(), Eigen::Vector3f::UnitY()};
  float spread_m2[2] = {0.0f, 0.0f};
  bool bent = false;  // mostly inside concave corners' bands: its fit may be bent, and nothing is left
                      // to check it against (concave_corners.hpp); gravity does not use it
};

// Least-squares plane of the segment's cells (centroid, normal, rms).
void fit_segment(const NormalGrid& grid, Segment& s);

// Grows segments with the "last normal" model: a neighbour joins when its
// normal is close to the normal of the cell it is reached from and it lies on
// that cell's tangent plane. Drops segments smaller than the scaled minimum.
// `labels` (reused) gets the segment index per cell or -1.
std::vector<Segment> grow_regions(const NormalGrid& grid, const RegionGrowingConfig& cfg, int image_width,
                                  int image_height, std::vector<int>& labels);

}  // namespace stairs
