// Where a top landing ends: a vertical face standing on the model's top level beyond its last
// nosing and facing down the flight (a wall, a door). On a landing with no step in view the level
// beneath fixes only the camera's height; this face fixes its position along the stair, as a riser
// does on the flight.
#pragma once

#include "common/types.hpp"
#include "tracker/pose.hpp"
#include "tracker/stair_map.hpp"

#include <optional>

namespace stairs {

struct EndWallConfig;
struct StairPriorConfig;

// Averages the end wall an observation shows (a plane no step owns, at `pose`, whose position along
// the stair may be `pose_uncertainty_m` off) into the map; confirmed after `min_observations`
// observations. Forgets it once the model has a step at or beyond it (a step is no wall).
void note_end_wall(StairMap& map, const Observation& obs, const Pose4& pose, double pose_uncertainty_m,
                   const EndWallConfig& c, const StairPriorConfig& stair, int max_average_weight,
                   int min_observations);

// The confirmed end wall's x (W), if the map has one beyond its last step.
std::optional<double> end_wall_x_m(const StairMap& map);

}  // namespace stairs
