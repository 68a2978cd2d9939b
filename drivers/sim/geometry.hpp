// A Scene as render primitives: one-sided planar quads (every face of the
// axis-aligned boxes a stair is made of, plus the ramp) and capped cylinders.
#pragma once

#include "drivers/sim/scene.hpp"

#include <array>
#include <vector>

namespace stairs::sim {

enum class FacePart : int8_t { Other = 0, Riser = 1, Tread = 2 };

struct Face {
  std::array<Eigen::Vector3d, 4> corners_m;  // convex, in order around the face, stair frame
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // outward: the visible side
  int step = -1;  // global step index (across flights) for risers and treads
  FacePart part = FacePart::Other;
};

struct Geometry {
  std::vector<Face> faces;
  std::vector<Cylinder> cylinders;
};

Geometry build_geometry(const Scene& s);

}  // namespace stairs::sim
