// Steps the motion prior alone placed: a frame with nothing on the model (the
// next flight seen from the last one, the robot's body pitching up at its foot)
// is merged at the prior's pose, so its steps lie off the steps before them by
// as much as the prior was off, centimetres where one frame measures millimetres.
// The link is kept open, with that uncertainty, until one registered frame sees
// steps on both sides of it; that frame's steps measure the offset, and the
// map's part beyond the link is moved by it (one observation holds both parts
// rigidly, as the thesis' merge (5.2) takes each frame's steps in one pose).
#pragma once

#include "tracker/merge.hpp"
#include "tracker/stair_map.hpp"

#include <Eigen/Core>

#include <optional>
#include <vector>

namespace stairs {

struct MergeConfig;
struct StairPriorConfig;

// After a merge the prior placed: each step that merge inserted next to a step the
// model held before opens a link to it.
void open_prior_links(StairMap& map);

// A link the observation sees both sides of, and the offset its steps measure: the map's
// steps from `from` on (and its end wall beyond them) are to move by `shift_m` (x, z).
struct LinkClosure {
  size_t from = 0;
  Eigen::Vector2d shift_m = Eigen::Vector2d::Zero();
};

// The model's first open link, where the observed steps (in the model frame, as registered) see
// both sides of it (the part beyond reaching to the next open link), with the offset they measure:
// the median residual of the steps beyond it less that of the steps before it (the registration's
// own offset cancels). nullopt where they do not, or the offset exceeds merge.link_shift_fraction
// of a tread or a riser (then a step may have matched its neighbour).
std::optional<LinkClosure> measure_prior_link(const StairMap& map, const std::vector<ObservedStep>& observed,
                                              const MergeConfig& c, const StairPriorConfig& stair);

// Moves the steps from `closure.from` on (planes' points, tread extents, the end wall
// beyond them) and closes the link.
void close_prior_link(StairMap& map, const LinkClosure& closure);

}  // namespace stairs
