// The tracker's internal model: steps of one straight stair in the model frame
// W (x along the ascending direction, y left, z up, fixed at the seed). The
// published StairModel is W shifted to the model's own first riser.
#pragma once

#include "common/median.hpp"

#include <Eigen/Core>

#include <vector>

namespace stairs {

struct StairPriorConfig;

// A running mean that turns into an exponential one after `cap` samples, so
// the model keeps following slow drift.
struct RunningMean {
  double value = 0.0;
  int count = 0;
  void add(double x, int cap) {
    ++count;
    value += (x - value) / std::min(count, cap);
  }
  bool known() const { return count > 0; }
};

struct MapStep {
  RunningMean riser_x_m;       // riser plane position along x
  RunningMean nosing_x_m;      // nosing edge position along x (where no riser was seen)
  RunningMean tread_z_m;       // tread plane height
  RunningMean edge_z_m;        // nosing height where no tread plane was seen: a depth jump, or a riser's top
                               // (under a nosing overhang the slab's underside, a slab's thickness low)
  RunningMean riser_height_m;  // as perception measured it (first step, gaps)
  RunningMean tread_depth_m;   // as perception measured it, nosing to nosing (the last step the model publishes)
  RunningMean overhang_m;      // the nosing's edge before the riser's face, where its slab was seen
  RunningMean y_min_m, y_max_m;  // lateral bounding box
  double tread_far_x_m = -1e9;   // farthest observed back edge of the tread (of its visible part: a lower bound)
  int confirmations = 0;
  int last_merge = -1;           // the StairMap::merges count of the last observation that saw it
  bool reconstructed = false;    // filled in between seen steps, never observed
  bool on_seen_floor = false;    // its riser stands on a level seen deeper than any tread (a floor or a
                                 // landing): what lies before it is known, not just one rise below
  double prior_link_m = 0.0;     // > 0: the motion prior alone placed it (and the steps placed with it) next to
                                 // the step before it, this far off at most along the stair (m); 0 once a
                                 // registered frame saw both (prior_links.hpp)
  std::vector<Eigen::Vector3f> riser_points, tread_points;  // W, ICP rejections, capped
  int riser_points_seen = 0, tread_points_seen = 0;          // for the cyclic cap

  double x() const { return riser_x_m.known() ? riser_x_m.value : nosing_x_m.value; }
  bool tread_z_settled = false;  // the tread plane seen in merge.min_tread_plane_observations observations
  // A tread plane measures the height once settled; edges stand in until then.
  double z() const {
    return tread_z_m.known() && (tread_z_settled || !edge_z_m.known()) ? tread_z_m.value : edge_z_m.value;
  }
};

struct StairMap {
  std::vector<MapStep> steps;  // sorted by x (bottom to top)
  int merges = 0;              // observations merged
  // A vertical face standing on the top level beyond the last step and facing down the flight (the
  // wall or door where a top landing ends; tracker/end_wall.hpp): its position along x, and whether
  // enough observations saw it to use it.
  RunningMean end_wall_x_m;
  RunningMean end_wall_uncertainty_m;  // how far off the poses it was seen from may have been (mean)
  bool end_wall_confirmed = false;
  bool empty() const { return steps.empty(); }
};

// Typical riser height and tread depth of the model (medians of adjacent
// steps), or the configured defaults while the model is too small.
double typical_riser_m(const StairMap& map, const StairPriorConfig& c);
double typical_tread_m(const StairMap& map, const StairPriorConfig& c);
// One typical step along the flight (x: tread, z: rise): a periodic flight repeats itself by it.
Eigen::Vector3d typical_step_m(const StairMap& map, const StairPriorConfig& c);
// Height of the level at x (W): the tread of the last step whose edge is at or
// behind x, the floor before the first.
double surface_z_m(const StairMap& map, double x_m, const StairPriorConfig& c);

// The surface at x averaged over one typical tread around it: the stair's mean
// slope on a flight, level on a landing or floor (what a walker's head follows).
double mean_surface_z_m(const StairMap& map, double x_m, const StairPriorConfig& c);

// Whether the way from a_m to b_m along the stair reaches where a flight meets a level (its first or
// last nosing, or one beside a landing, within half a typical tread: where mean_surface_z_m bends).
// A height carried along the mean slope holds on a flight and on a level for any carrier; across a
// bend it changes by the slope times how far the carrier's feet lag its camera, which nothing measures
// without a mount.
bool reaches_a_flight_end(const StairMap& map, double a_m, double b_m, const StairPriorConfig& c);

// Height of the floor below the first step.
double floor_z_m(const StairMap& map, const StairPriorConfig& c);

}  // namespace stairs
