// 4-DoF registration of one observation to the model (thesis 5.1 on the
// stair's structure): yaw in closed form from the plane orientations, then a
// point-to-plane ICP whose unknowns are the x and z offsets, with coarse-to-fine
// correspondence thresholds. Riser points fix x, tread points fix z, nosings both.
#pragma once

#include "common/types.hpp"
#include "tracker/pose.hpp"
#include "tracker/stair_map.hpp"

#include <optional>
#include <vector>

namespace stairs {

struct RegistrationConfig;
struct StairPriorConfig;

// Observation samples in the gravity-aligned camera frame.
struct RegistrationInput {
  std::vector<Eigen::Vector3d> riser_points, tread_points, nosings;
  std::vector<Eigen::Vector3d> foot_points;  // the level the lowest step stands on (also among tread_points)
};

// The level the lowest seen step stands on: the index of a horizontal plane no
// step owns, within foot_max_offset_rise_fraction of a rise of where that
// step's riser begins and reaching to within foot_max_gap_m of it along the
// stair; -1 if none.
int foot_plane(const Observation& obs, const RegistrationConfig& c);

// Which of the observation's planes a step owns (its riser or its tread).
std::vector<bool> planes_owned_by_steps(const Observation& obs);

// Every level in view (tread and landing planes) as tread points: a frame without steps.
RegistrationInput level_points(const Observation& obs, const RegistrationConfig& c);

// Every riser, level and depth-jump nosing in view: a frame without steps, placed on the model's planes.
RegistrationInput planes_in_view(const Observation& obs, const RegistrationConfig& c);

// The steps' planes and nosings, and the level the lowest step stands on.
RegistrationInput registration_input(const Observation& obs, const RegistrationConfig& c);

// Direction of the stair axis (riser normals, tread edges) in the gravity-aligned
// camera frame, as an angle about z modulo pi; nullopt without risers or treads.
std::optional<double> observed_axis_angle_rad(const Observation& obs);

// The yaw (gravity frame -> model) closest to `prior_yaw_rad` that maps the
// observed axis onto the model's x axis.
double yaw_from_axis(double axis_angle_rad, double prior_yaw_rad);

struct Registration {
  Pose4 pose;
  double rmse_m = -1.0;       // over points within accept_distance_m
  double inlier_ratio = 0.0;  // share of the points within the model's extent that lie within
                              // accept_distance_m of it, the lower of risers' and treads'
  int inliers = 0;
  int within = 0;             // points within the model's extent (none: nothing to register against)
  int x_inliers = 0;          // riser points and nosings that agree at the final pose: all that fixes x
                              // (treads fix only z)
  int x_within = 0;           // riser points and nosings within the model's extent
  int nosing_inliers = 0;     // nosings that agree at the final pose
  int end_wall_inliers = 0;   // riser points among x_inliers that agree with the model's end wall
};

// The next flight seen across a landing: at `pose` every riser point and nosing lies beyond the
// model's ends, so nothing can fix the position along the stair, while the level the lowest step
// stands on lies on the model's levels (its top level running on beyond the part seen so far).
// Returns that level's share of points within accept_distance_m of them; 0 without such a level
// or when a riser or nosing lies within the model.
double foot_agreement_beyond_model(const RegistrationInput& in, const StairMap& map, const Pose4& pose,
                                   const RegistrationConfig& c, const StairPriorConfig& stair);

// How much of an observation agrees with the model at a registration's pose: its agreeing plane
// points, each agreeing nosing counted as nosing_weight_points of them (as in the ICP).
double agreeing_points(const Registration& reg, const RegistrationConfig& c);

// Registers with yaw fixed to `initial.yaw_rad`, starting from `initial`.
Registration register_to_map(const RegistrationInput& in, const StairMap& map, const Pose4& initial,
                             const RegistrationConfig& c, const StairPriorConfig& stair);

}  // namespace stairs
