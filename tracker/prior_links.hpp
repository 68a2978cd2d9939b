// Steps the motion prior alone placed: a frame with nothing on the model (the
// next flight seen from the last one, the robot's body pitching up at its foot)
// is merged at the prior's pose, so its steps lie off the steps before them by
// as much as the prior was off, centimetres where one frame measures millimetres.
// The link is kept open, with that uncertainty, until one registered frame sees
// steps on both sides of it; that frame's steps measure the offset, and the
// map's part beyond the link is moved by it (one observation holds both parts
// rigidly, as the thesis' merge (5.2) takes each frame's steps in one pose).
// Until then the camera, registered on one part, is that uncertain relative to
// the other: model_output.cpp keeps the step beneath it unknown near its nosings.
#pragma once

#include "tracker/merge.hpp"
#include "tracker/stair_map.hpp"

#include <optional>
#include <vector>

namespace stairs {

struct MergeConfig;
struct StairPriorConfig;

// After a merge the prior placed: each step that merge inserted next to a step the
// model held before opens a link to it, as uncertain as the prior's position along the stair.
void open_prior_links(StairMap& map, double uncertainty_m);

// After a merge registered on the model: steps it inserted right before an open link, where the
// frame's steps lie beyond them (`registered_on_x_m`: their middle along the stair), were placed as
// the steps beyond the link are, and join their part (the frame saw nothing before the link, else
// it was closed): a flight's first step seen after its others stood before the link, and the next
// frame measured the link against it alone, as closed.
void extend_prior_links(StairMap& map, double registered_on_x_m);

// Whether the model holds a link the prior placed that no frame has measured yet.
bool any_open_prior_link(const StairMap& map);

// Per step, how far off along the stair the motion prior may have placed it relative to the step
// nearest `registered_on_x_m` (the steps the camera was registered on): the open links between
// them. Empty while no link is open.
std::vector<double> prior_link_uncertainties_m(const StairMap& map, double registered_on_x_m);

// A link the observation sees both sides of, and the offset its steps measure along the stair: the
// map's steps from `from` on (and its end wall beyond them) are to move by `shift_x_m`. Along the
// stair only: the prior's steps stand at the heights their own frame observed (the tracker places
// such a frame at its observed height), and a height residual between two parts mixes a tread
// plane's height with a nosing edge's (a hand-held descent's top flight moved 1 cm down on it, its
// camera's height 0.2 -> 0.8 cm off).
struct LinkClosure {
  size_t from = 0;
  double shift_x_m = 0.0;
};

// The model's first open link, where the observed steps (in the model frame, as registered) see
// `min_steps` or more on each side of it (the part beyond reaching to the next open link), with the
// offset they measure: the median residual of the steps beyond it less that of the steps before it
// (the registration's own offset cancels). One step a side is one nosing's noise (a D435's 3 m
// away scatter by centimetres: a hand-held level descent's model moved 1.8 cm on one and grew a
// false step). nullopt where they do not, or the offset exceeds merge.link_shift_fraction of a
// tread (then a step may have matched its neighbour).
std::optional<LinkClosure> measure_prior_link(const StairMap& map, const std::vector<ObservedStep>& observed,
                                              const MergeConfig& c, const StairPriorConfig& stair, int min_steps);

// Moves the steps from `closure.from` on (planes' points, tread extents, the end wall
// beyond them) and closes the link.
void close_prior_link(StairMap& map, const LinkClosure& closure);

}  // namespace stairs
