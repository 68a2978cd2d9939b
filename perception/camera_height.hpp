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

// Where the point straight beneath the camera is in view, the lowest surface
// spanning it is beneath. Otherwise the image's lowest row meets the scene
// some way ahead of the camera; what
// lies between is out of view, and a step edge there cannot be ruled out by
// this frame alone. A detected flight rules it out for one surface: the level
// on the camera's side of the flight's first edge (the floor at the first
// riser's foot going up, the top landing at the first nosing going down),
// when that level reaches the lowest row, is the lowest surface there, and is
// seen over more than the flight's longest run (plus the regularity
// tolerance): then it is no tread of this flight whose front is out of view.
// Everywhere else the height is unknown; the tracker's model knows it on the
// flight. Still ambiguous: a mid landing seen from the flight's last tread.
std::optional<double> camera_height(const PlaneSet& ps, const std::vector<Step>& steps, Direction direction,
                                    const Intrinsics& K, double pitch_deg, const PerceptionConfig& cfg);

}  // namespace stairs
