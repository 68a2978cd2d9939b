#include "tracker/merge.hpp"

#include "tracker/config.hpp"

#include <algorithm>
#include <cmath>

namespace stairs {

namespace {

const Plane* plane_at(const Observation& obs, int index) {
  return index >= 0 && index < static_cast<int>(obs.planes.size()) ? &obs.planes[index] : nullptr;
}

void add_lateral_extent(const Plane& p, const Eigen::Isometry3d& pose, std::optional<double>& lo, std::optional<double>& hi) {
  for (const auto& corner : p.corners) {
    const double y = (pose * corner.cast<double>()).y();
    lo = lo ? std::min(*lo, y) : y;
    hi = hi ? std::max(*hi, y) : y;
  }
}

// Keeps at most `cap` points, overwriting cyclically once full.
void keep_points(std::vector<Eigen::Vector3f>& kept, int& seen, const Eigen::Vector3f& p, int cap) {
  if (cap <= 0) return;
  if (static_cast<int>(kept.size()) < cap)
    kept.push_back(p);
  else
    kept[seen % cap] = p;
  ++seen;
}

// The ICP rejections of a matched plane: points farther than the finest
// threshold from the model plane (`axis` 0 = riser x, 2 = tread z).
void add_rejections(const Plane& p, const Eigen::Isometry3f& pose, int axis, double plane_m, double reject_m, int cap,
                    std::vector<Eigen::Vector3f>& kept, int& seen) {
  for (const auto& q : p.points) {
    const Eigen::Vector3f w = pose * q;
    if (std::abs(w[axis] - plane_m) > reject_m) keep_points(kept, seen, w, cap);
  }
}

void update(MapStep& m, const ObservedStep& o, const Pose4& pose, const MergeConfig& c, double min_distance_m) {
  const int cap = c.max_average_weight;
  if (o.riser_x_m) m.riser_x_m.add(*o.riser_x_m, cap);
  m.nosing_x_m.add(o.nosing_m.x(), cap);
  // A tread's plane measures its height once it has been seen in enough
  // observations; an edge alone only until then.
  if (o.tread_z_m) m.tread_z_m.add(*o.tread_z_m, cap);
  else m.edge_z_m.add(o.nosing_m.z(), cap);
  m.tread_z_settled = m.tread_z_m.count >= c.min_tread_plane_observations;
  if (o.riser_height_m) m.riser_height_m.add(*o.riser_height_m, cap);
  if (o.overhang_m) m.overhang_m.add(*o.overhang_m, cap);
  if (o.tread_far_x_m) m.tread_far_x_m = std::max(m.tread_far_x_m, *o.tread_far_x_m);
  if (o.tread_depth_m) m.tread_depth_m.add(*o.tread_depth_m, cap);
  if (o.y_min_m) m.y_min_m.add(*o.y_min_m, cap);
  if (o.y_max_m) m.y_max_m.add(*o.y_max_m, cap);
  ++m.confirmations;
  m.reconstructed = false;
  const Eigen::Isometry3f to_model = pose.isometry().cast<float>();
  if (o.riser)
    add_rejections(*o.riser, to_model, 0, m.x(), min_distance_m, c.max_plane_points, m.riser_points,
                   m.riser_points_seen);
  if (o.tread)
    add_rejections(*o.tread, to_model, 2, m.z(), min_distance_m, c.max_plane_points, m.tread_points,
                   m.tread_points_seen);
}

// A new step must keep the stair rising and running: above every step before
// it and below every step after it, by at least min_rise_fraction of a riser,
// and along the flight from each by at least min_run_fraction of a tread (a
// riser has one nosing: a second one at its x is the same step measured low,
// as a riser's top under a nosing's slab is).
bool fits_between(const StairMap& map, size_t at, const ObservedStep& o, double riser, double tread,
                  const MergeConfig& c) {
  const double rise = c.min_rise_fraction * riser - c.monotonic_tolerance_m;
  const double run = c.min_run_fraction * tread - c.monotonic_tolerance_m;
  if (at > 0 && (o.z() - map.steps[at - 1].z() < rise || o.x() - map.steps[at - 1].x() < run)) return false;
  if (at < map.steps.size() && (map.steps[at].z() - o.z() < rise || map.steps[at].x() - o.x() < run)) return false;
  return true;
}

// Normalised distance of an observed step from a model step (dz / riser +
// dx / tread), or infinity beyond the match tolerances.
double distance(const ObservedStep& o, const MapStep& m, double riser, double tread, const MergeConfig& c) {
  const double dz = std::abs(o.z() - m.z()) / riser;
  const double dx = std::abs(o.x() - m.x()) / tread;
  return dz < c.match_riser_fraction && dx < c.match_tread_fraction ? dz + dx : 1e9;
}

}  // namespace

bool matches(const StairMap& map, const ObservedStep& o, const MapStep& m, const MergeConfig& c,
             const StairPriorConfig& stair) {
  return distance(o, m, typical_riser_m(map, stair), typical_tread_m(map, stair), c) < 1e9;
}

bool agrees_where_it_overlaps(const StairMap& map, const std::vector<ObservedStep>& observed, const MergeConfig& c,
                              const StairPriorConfig& stair) {
  if (map.empty()) return true;
  const double riser = typical_riser_m(map, stair);
  const double tread = typical_tread_m(map, stair);
  const double lo = map.steps.front().x() - c.match_tread_fraction * tread;
  const double hi = map.steps.back().x() + c.match_tread_fraction * tread;
  for (const ObservedStep& o : observed) {
    if (o.x() < lo || o.x() > hi) continue;
    const bool matched = std::any_of(map.steps.begin(), map.steps.end(),
                                     [&](const MapStep& m) { return distance(o, m, riser, tread, c) < 1e9; });
    if (!matched) return false;
  }
  return true;
}

const ObservedStep& lowest_step(const std::vector<ObservedStep>& observed) {
  return *std::min_element(observed.begin(), observed.end(),
                           [](const ObservedStep& a, const ObservedStep& b) { return a.nosing_m.z() < b.nosing_m.z(); });
}

std::vector<ObservedStep> observed_steps(const Observation& obs, const Pose4& pose) {
  std::vector<ObservedStep> out;
  const Eigen::Isometry3d to_model = pose.isometry();
  for (const Step& s : obs.steps) {
    ObservedStep o;
    o.nosing_m = to_model * s.nosing_m;
    o.riser = plane_at(obs, s.riser_plane);
    o.tread = plane_at(obs, s.tread_plane);
    if (o.riser) {
      // At its face as perception placed it (the box's corners: the median of its middle rows,
      // not the mean of all its cells, which a nosing's slab front pulls forward).
      Eigen::Vector3d face = Eigen::Vector3d::Zero();
      for (const auto& corner : o.riser->corners) face += 0.25 * corner.cast<double>();
      o.riser_x_m = (to_model * face).x();
      add_lateral_extent(*o.riser, to_model, o.y_min_m, o.y_max_m);
    }
    if (o.tread) {
      o.tread_z_m = o.tread->centroid.z() + pose.t_m.z();
      double far = -1e9;
      for (const auto& corner : o.tread->corners) far = std::max(far, (to_model * corner.cast<double>()).x());
      o.tread_far_x_m = far;
      add_lateral_extent(*o.tread, to_model, o.y_min_m, o.y_max_m);
    }
    // An inferred rise is perception's prior, not a measurement: the model regularises itself.
    if (!(s.inferred & kStepRiserInferred)) o.riser_height_m = s.riser_height_m;
    // A tread cut by the view or by the step above it shows only part of its depth: no measurement.
    if (!(s.inferred & kStepTreadPartial)) o.tread_depth_m = s.tread_depth_m;
    out.push_back(o);
  }
  return out;
}

std::vector<int> match_steps(const StairMap& map, const std::vector<ObservedStep>& observed, const MergeConfig& c,
                             const StairPriorConfig& stair) {
  const double riser = typical_riser_m(map, stair);
  const double tread = typical_tread_m(map, stair);
  std::vector<int> match(observed.size(), -1);
  std::vector<bool> taken(map.steps.size(), false);
  for (size_t i = 0; i < observed.size(); ++i) {
    double best = 1e9;
    for (size_t k = 0; k < map.steps.size(); ++k) {
      if (taken[k]) continue;
      const double d = distance(observed[i], map.steps[k], riser, tread, c);
      if (d < best) {
        best = d;
        match[i] = static_cast<int>(k);
      }
    }
    if (match[i] >= 0) taken[match[i]] = true;
  }
  return match;
}

int merge(StairMap& map, const std::vector<ObservedStep>& observed, const Pose4& pose, const MergeConfig& c,
          const StairPriorConfig& stair, double min_distance_m) {
  const double riser = typical_riser_m(map, stair);
  const double tread = typical_tread_m(map, stair);
  // Match against the model as it was before this observation.
  const std::vector<int> match = match_steps(map, observed, c, stair);
  ++map.merges;
  for (size_t i = 0; i < observed.size(); ++i)
    if (match[i] >= 0) {
      update(map.steps[match[i]], observed[i], pose, c, min_distance_m);
      map.steps[match[i]].last_merge = map.merges;
    }

  int inserted = 0;
  for (size_t i = 0; i < observed.size(); ++i) {
    if (match[i] >= 0 || static_cast<int>(map.steps.size()) >= c.max_model_steps) continue;
    const ObservedStep& o = observed[i];
    const auto at = std::lower_bound(map.steps.begin(), map.steps.end(), o.x(),
                                     [](const MapStep& s, double x) { return s.x() < x; }) -
                    map.steps.begin();
    if (!fits_between(map, static_cast<size_t>(at), o, riser, tread, c)) continue;
    MapStep m;
    update(m, o, pose, c, min_distance_m);
    m.last_merge = map.merges;
    map.steps.insert(map.steps.begin() + at, std::move(m));
    ++inserted;
  }
  return inserted;
}

}  // namespace stairs

