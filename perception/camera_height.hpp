// The camera's height above the surface beneath it (DESIGN.md camera pose
// `height_m`), from one frame, only where that frame shows the surface really
// is beneath: unknown beats wrong (issue 15).
#pragma once

#include "common/types.hpp"
#include "perception/config.hpp"
#include "perception/plane_geometry.hpp"

#include <optional>
#include <vector>

namespace stairs {

// Height over the lowest surface spanning the point straight beneath, when in view; else over the
// level before the flight if it shows more than the longest run (no tread hides below the image).
// Otherwise unknown: the tracker's model knows better (issue 15: unknown beats wrong).
std::optional<double> camera_height(const PlaneSet& ps, const std::vector<Step>& steps, Direction direction,
                                    const Intrinsics& K, double pitch_deg, const CameraHeightConfig& cfg,
                                    const StairConfig& stair, float run_tolerance_m);

}  // namespace stairs
