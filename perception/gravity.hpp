// Stage 3: gravity from weighted horizontal normals (thesis Algorithm 4):
// pitch, roll and the rotation into the gravity-aligned camera frame.
#pragma once

#include "perception/region_growing.hpp"

#include <limits>
#include <optional>

namespace stairs {

// Up in the optical frame (thesis 3.5): the segment normal near image up (near the previous up
// instead, when given: a camera looking straight down sees the treads face-on) with the most parallel
// support. Of the set's members (with a prior, of every
// plane near it), the one most planes agree with (parallel or perpendicular within consensus_deg)
// chooses the treads that up is fitted to: least squares, each weighted by how well its fit knows
// its normal (thesis Algorithm 4 weights by support alone). Segments marked bent
// (concave_corners.hpp) take no part. Nothing if none fits. `carried` (when
// given): up's pitch (its tilt along the levelled optical axis) is the prior's,
// measured by no plane of this frame to within consensus_deg (walls along the view, no tread
// that knows its normal), weighed against what the planes know of it by `prior_information`
// (1 / rad^2: how well the prior's pitch is still known; infinite keeps the prior's).
std::optional<Eigen::Vector3f> estimate_up(const std::vector<Segment>& segments, const GravityConfig& cfg,
                                           const std::optional<Eigen::Vector3f>& prior = std::nullopt,
                                           bool* carried = nullptr,
                                           double prior_information = std::numeric_limits<double>::infinity());

// Pose from the up vector: pitch, roll (DESIGN.md conventions) and
// gravity_rotation (optical -> x forward, y left, z up). Height and distance
// are left empty.
CameraPose pose_from_up(const Eigen::Vector3f& up_optical);

}  // namespace stairs
