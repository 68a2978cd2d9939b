// Camera pose scalars of DESIGN.md "Frames and units", from an exact pose.
#pragma once

#include "drivers/sim/scene.hpp"

#include <optional>

namespace stairs::sim {

// Optical axis above (+) or below (-) the horizon, degrees.
double pitch_deg(const Eigen::Isometry3d& camera_optical_in_stair);
// Rotation about the optical axis, positive = camera's right side down, degrees.
double roll_deg(const Eigen::Isometry3d& camera_optical_in_stair);
// Camera centre above the walkable surface directly beneath it.
double height_m(const Scene& s, const Eigen::Isometry3d& camera_optical_in_stair);
// Horizontal distance to the first step edge ahead: the bottom riser of the
// next flight when looking up the stair (+x), the top nosing of the flight
// below when looking down (-x); nullopt over a flight or with no flight ahead.
std::optional<double> distance_m(const Scene& s, const Eigen::Isometry3d& camera_optical_in_stair);

}  // namespace stairs::sim
