// The camera's height above the surface beneath it (DESIGN.md camera pose
// `height_m`), from one frame, only where that frame shows the surface really
// is beneath: unknown beats wrong (issue 15).
#pragma once

#include "common/types.hpp"
#include "perception/config.hpp"
#include "perception/normals.hpp"
#include "perception/plane_geometry.hpp"

#include <optional>

namespace stairs {

// Height above the surface straight beneath, when in view: the level the grid's cells (`R`: optical
// -> gravity-aligned) show around the plumb line. Otherwise unknown, unless a configured mount (the
// top-level "mount") on a level carrier names the level at its height as the ground (issue 15:
// unknown beats wrong; the tracker's model knows better).
std::optional<double> camera_height(const PlaneSet& ps, const NormalGrid& grid, const Eigen::Matrix3f& R,
                                    const Intrinsics& K, double pitch_deg, double roll_deg,
                                    const CameraHeightConfig& cfg, const MountConfig& mount);

}  // namespace stairs
