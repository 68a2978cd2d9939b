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

// The lowest surface spanning the point straight beneath, where that is in
// view. Else the level before a detected flight's first edge, if it reaches
// the image's lowest row, is the lowest there and shows more than the
// longest run (+ run_tolerance_m): then no tread's front hides out of view.
// Otherwise unknown (the tracker's model knows). Levels within
// stair.same_level_m are one; the fallback run is stair.tread_max_m.
std::optional<double> camera_height(const PlaneSet& ps, const std::vector<Step>& steps, Direction direction,
                                    const Intrinsics& K, double pitch_deg, const CameraHeightConfig& cfg,
                                    const StairConfig& stair, float run_tolerance_m);

}  // namespace stairs
