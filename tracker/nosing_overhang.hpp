// A nosing overhang (DIN 18065: the tread's front edge stands 2-5 cm before the
// riser below it) measured from the riser planes going up: the slab's front
// face at a riser's top stands before its face. Registration and merge keep
// the risers' faces (what is seen on every frame); the model's published
// nosings, and the step beneath the camera, sit at the edge, as the nosing is
// defined (../shared/DESIGN.md: the convex edge where riser meets tread).
#pragma once

#include "common/types.hpp"
#include "tracker/stair_map.hpp"

#include <Eigen/Geometry>

#include <optional>

namespace stairs {

struct OverhangConfig;

// The overhang one riser plane shows: the median position along the stair of
// its middle band less that of its top band, its points taken to the model by
// `to_model`; nullopt unless its top reaches the step's nosing height (the
// slab in view) and both bands hold enough points.
std::optional<double> riser_overhang_m(const Plane& riser, const Eigen::Isometry3d& to_model, double nosing_z_m,
                                       const OverhangConfig& c);

// The flight's overhang: the median of its steps' measured overhangs, within
// [0, max_m]; 0 until min_steps steps have one (a stair without risers in view,
// e.g. only ever seen going down, keeps its nosings as seen).
double flight_overhang_m(const StairMap& map, const OverhangConfig& c);

}  // namespace stairs
