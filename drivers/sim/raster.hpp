// Z-buffer rasterisation of the scene's faces and cylinders for a pinhole
// camera: the depth of a plane is affine in 1/z across the image, so a face
// costs one multiply-add per covered pixel. Cylinders are ray-cast inside
// their screen bounding box.
#pragma once

#include "drivers/sim/geometry.hpp"

#include "common/types.hpp"

#include <cstdint>
#include <vector>

namespace stairs::sim {

struct ZBuffer {
  int width = 0, height = 0;
  std::vector<float> inv_z;  // 1/m, 0 = nothing hit
  std::vector<int32_t> id;   // face index, faces.size() + cylinder index, -1 = nothing

  void reset(int w, int h);
};

constexpr double kNearPlane_m = 0.05;

// Renders `g` seen from a camera whose optical frame has pose camera_in_stair.
void rasterise(const Geometry& g, const Eigen::Isometry3d& camera_in_stair, const Intrinsics& K, ZBuffer& zb);

// Unit normal (stair frame) of primitive `id` at stair-frame point p.
Eigen::Vector3d primitive_normal(const Geometry& g, int32_t id, const Eigen::Vector3d& p);

}  // namespace stairs::sim
