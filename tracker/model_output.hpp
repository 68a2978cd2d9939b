// The published StairModel: the model's confirmed steps in the stair frame
// (origin on the floor beneath the model's first nosing: the foot of its first
// riser, less a nosing overhang; nosing_overhang.hpp), split into flights at
// landings, with planes and the camera on the stair.
#pragma once

#include "common/mount.hpp"
#include "common/types.hpp"
#include "tracker/pose.hpp"
#include "tracker/stair_map.hpp"

#include <vector>

namespace stairs {

struct ConfirmationConfig;
struct StairPriorConfig;

// Fills out.flights, out.planes, the camera fields and, with a configured mount, the base fields
// (issue 15: outputs in the robot's base frame); leaves state, counters, direction and quality to
// the caller. `camera` is the gravity-aligned camera frame -> W pose; `gravity_rotation` is the
// observation's optical -> gravity. `overhang_m`: the nosing's edge stands this far before the face of
// a seen riser (nosing_overhang.hpp); the published nosings and the step beneath use the edge.
// `x_uncertainty_m`: how far off the camera's position along the stair may be (0 where measured); the
// surface beneath is unknown where a nosing lies that close. `link_m` (empty, or one per map step): how
// far off the motion prior may have placed each step relative to those the camera was registered on
// (prior_links.hpp); it adds to x_uncertainty_m near that step's nosing, and the first published
// step's to the camera's published uncertainty. `just_merged`: the frame this model is for is the one
// the map merged last (its steps that continue the flight go with it, model_output.cpp).
void fill_model(const StairMap& map, bool just_merged, const Pose4& camera, bool camera_valid, double x_uncertainty_m,
                const std::vector<double>& link_m, const Eigen::Quaterniond& gravity_rotation, const ConfirmationConfig& c,
                const StairPriorConfig& stair, const MountConfig& mount, double overhang_m, StairModel& out);

// The model's steps, bottom to top, in its camera's gravity-aligned frame: what the tracker knows
// around the camera, out of view included. Empty when the camera is not valid.
std::vector<Step> steps_from_camera(const StairModel& model);

}  // namespace stairs
