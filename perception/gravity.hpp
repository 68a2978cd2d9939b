// Stage 3: gravity from weighted horizontal normals (thesis Algorithm 4):
// pitch, roll and the rotation into the gravity-aligned camera frame.
#pragma once

#include "perception/region_growing.hpp"

#include <optional>

namespace stairs {

// Up direction in the optical frame, or nothing when no plane can be horizontal.
// Candidates are segment normals within max_tilt of image up (-y); each scores
// the support of the segments parallel to it; the best one's parallel set
// gives the support-weighted mean normal. With a prior (the previous frame's
// up), only candidates within gravity_prior_max_deg of it count; without one
// there, up is perpendicular to the vertical planes (risers, walls).
std::optional<Eigen::Vector3f> estimate_up(const std::vector<Segment>& segments, const GravityConfig& cfg,
                                           const std::optional<Eigen::Vector3f>& prior = std::nullopt);

// Pose from the up vector: pitch, roll (DESIGN.md conventions) and
// gravity_rotation (optical -> x forward, y left, z up). Height and distance
// are left empty.
CameraPose pose_from_up(const Eigen::Vector3f& up_optical);

}  // namespace stairs
