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
