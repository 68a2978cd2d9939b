// Stage 2: planar segments by region growing on the normal grid.
#pragma once

#include "perception/normals.hpp"

#include <cmath>
#include <vector>

namespace stairs {

// Sums of points and of their products (double: the centred form's precision
// at a few metres): a least-squares plane of any set of cells, and of a set
// with some of its cells taken away, without passing over them again.
struct PlaneSums {
  double n = 0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0;
  void add(const Eigen::Vector3f& point) {
    const Eigen::Vector3d p = point.cast<double>();
    n += 1;
    sum += p;
    xx += p.x() * p.x(), xy += p.x() * p.y(), xz += p.x() * p.z();
    yy += p.y() * p.y(), yz += p.y() * p.z(), zz += p.z() * p.z();
  }
  PlaneSums operator-(const PlaneSums& o) const {
    PlaneSums d;
    d.n = n - o.n, d.sum = sum - o.sum;
    d.xx = xx - o.xx, d.xy = xy - o.xy, d.xz = xz - o.xz, d.yy = yy - o.yy, d.yz = yz - o.yz, d.zz = zz - o.zz;
    return d;
  }
};

struct Segment {
  std::vector<int> cells;  // grid indices
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero();  // m, optical frame
  Eigen::Vector3f normal = Eigen::Vector3f::UnitZ();   // least-squares, towards the camera
  float rms_m = 0.0f;                                  // point-to-plane
  // In-plane axes of the cells' spread (unit, optical frame) and the variance along each, m^2:
  // how well the normal's tilt towards each is known (a thin strip's, across it, poorly).
  Eigen::Vector3f axis[2] = {Eigen::Vector3f::UnitX(), Eigen::Vector3f::UnitY()};
  float spread_m2[2] = {0.0f, 0.0f};
  PlaneSums sums;  // of all its cells
  bool bent = false;  // bent by a concave corner's band, with too little outside it to stand for its
                      // plane (concave_corners.hpp); gravity does not use it

  // Its size along the unit direction d (optical frame): its cells' spread along d, as the size of an
  // even strip with that variance (12 sigma^2 = size^2).
  float size_along_m(const Eigen::Vector3f& d) const {
    float var = 0.0f;
    for (int k = 0; k < 2; ++k) {
      const float a = axis[k].dot(d);
      var += spread_m2[k] * a * a;
    }
    return std::sqrt(12.0f * var);
  }
};

// Least-squares plane of the segment's cells (sums, centroid, normal, rms, axes).
void fit_segment(const NormalGrid& grid, Segment& s);
// The plane of `sums` into s (centroid, normal, rms, axes and spread; not its cells or sums).
void fit_plane(const PlaneSums& sums, Segment& s);

// Grows segments with the "last normal" model: a neighbour joins when its
// normal is close to the normal of the cell it is reached from and it lies on
// that cell's tangent plane. Drops segments smaller than the scaled minimum.
// Each plane is fitted to its segment's cells away from depth jumps
// (cfg.fit_jump_ratio: cells there mix two surfaces), facing as its cells' normals.
// `labels` (reused) gets the segment index per cell or -1.
std::vector<Segment> grow_regions(const NormalGrid& grid, const RegionGrowingConfig& cfg, int image_width,
                                  int image_height, std::vector<int>& labels);

}  // namespace stairs
