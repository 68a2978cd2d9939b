// Merging a registered observation into the model (thesis 5.2): steps match by
// tread height and riser/nosing position; matched steps average their planes and
// bounding boxes and take only the points the model does not explain yet; new
// steps are inserted where they belong along x when they keep the stair rising.
#pragma once

#include "common/types.hpp"
#include "tracker/pose.hpp"
#include "tracker/stair_map.hpp"

#include <optional>
#include <vector>

namespace stairs {

struct MergeConfig;
struct StairPriorConfig;

// One observed step expressed in the model frame W.
struct ObservedStep {
  std::optional<double> riser_x_m, tread_z_m, riser_height_m, tread_far_x_m;
  std::optional<double> overhang_m;  // the nosing's edge before the riser's face (nosing_overhang.hpp)
  std::optional<double> tread_depth_m;  // perception's nosing-to-nosing depth; none where the tread was cut
  Eigen::Vector3d nosing_m = Eigen::Vector3d::Zero();
  std::optional<double> y_min_m, y_max_m;
  const Plane* riser = nullptr;
  const Plane* tread = nullptr;
  double x() const { return riser_x_m ? *riser_x_m : nosing_m.x(); }
  double z() const { return tread_z_m ? *tread_z_m : nosing_m.z(); }
};

std::vector<ObservedStep> observed_steps(const Observation& obs, const Pose4& pose);
// The one with the lowest nosing; `observed` must not be empty.
const ObservedStep& lowest_step(const std::vector<ObservedStep>& observed);

// Whether every observed step within the model's extent (along x, half a
// tread beyond its ends) matches a model step: steps placed by a prior alone
// (nothing registered) must land on the model where they overlap it.
bool agrees_where_it_overlaps(const StairMap& map, const std::vector<ObservedStep>& observed, const MergeConfig& c,
                              const StairPriorConfig& stair);

// Whether an observed step matches a model step within merge's tolerances.
bool matches(const StairMap& map, const ObservedStep& o, const MapStep& m, const MergeConfig& c,
             const StairPriorConfig& stair);

// For each observed step the model step it matches (the nearest within merge's tolerances, each
// model step taken once, in the observation's order), or -1.
std::vector<int> match_steps(const StairMap& map, const std::vector<ObservedStep>& observed, const MergeConfig& c,
                             const StairPriorConfig& stair);

// Returns the number of new steps inserted.
int merge(StairMap& map, const std::vector<ObservedStep>& observed, const Pose4& pose, const MergeConfig& c,
          const StairPriorConfig& stair, double min_distance_m);

}  // namespace stairs
