#include "tracker/registration.hpp"

#include "tracker/config.hpp"
#include "tracker/end_wall.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace stairs {

namespace {

void sample(const Plane& p, int n, std::vector<Eigen::Vector3d>& out) {
  const size_t stride = std::max<size_t>(1, p.points.size() / static_cast<size_t>(n));
  for (size_t i = 0; i < p.points.size(); i += stride) out.push_back(p.points[i].cast<double>());
}

// The model's planes as bounded lines in the x-z profile.
struct Profile {
  std::vector<double> riser_x, riser_z_lo, riser_z_hi;
  int end_wall = -1;  // the riser face that is the model's end wall (end_wall.hpp), if any
  double top_seen_x = 0.0;  // how far along x the top level was seen (its nosing, or its tread's far edge)
  double tread_m = 0.0;     // the typical tread
  std::vector<double> tread_z, tread_x_lo, tread_x_hi;
  std::vector<double> tread_seen_x;  // how far along x each level was seen (the floor: all of it)
  std::vector<Eigen::Vector2d> nosing_xz;
  // Across the stair: the lateral extent its steps were seen over (infinite where none was).
  double y_lo = -std::numeric_limits<double>::infinity(), y_hi = std::numeric_limits<double>::infinity();
};

Profile profile(const StairMap& map, const StairPriorConfig& c) {
  Profile p;
  const double floor_z = floor_z_m(map, c);
  // The level the first riser stands on (the floor, or the landing the flight
  // below ends on) runs on before the stair: a lower flight seen beyond the
  // model's first riser registers its height on it.
  p.tread_z.push_back(floor_z);
  p.tread_x_lo.push_back(-std::numeric_limits<double>::infinity());
  p.tread_x_hi.push_back(map.steps.front().x());
  p.tread_seen_x.push_back(map.steps.front().x());
  const double tread = typical_tread_m(map, c);
  p.tread_m = tread;
  for (size_t i = 0; i < map.steps.size(); ++i) {
    const MapStep& s = map.steps[i];
    p.riser_x.push_back(s.x());
    p.riser_z_lo.push_back(i == 0 ? floor_z : map.steps[i - 1].z());
    p.riser_z_hi.push_back(s.z());
    p.tread_z.push_back(s.z());
    p.tread_x_lo.push_back(s.x());
    p.tread_x_hi.push_back(i + 1 < map.steps.size() ? map.steps[i + 1].x()
                                                    : std::max(s.tread_far_x_m, s.x() + tread));
    p.tread_seen_x.push_back(std::max(s.x(), s.tread_far_x_m));
    p.nosing_xz.emplace_back(s.x(), s.z());
    if (s.y_min_m.known()) p.y_lo = std::isinf(p.y_lo) ? s.y_min_m.value : std::min(p.y_lo, s.y_min_m.value);
    if (s.y_max_m.known()) p.y_hi = std::isinf(p.y_hi) ? s.y_max_m.value : std::max(p.y_hi, s.y_max_m.value);
  }
  p.top_seen_x = std::max(map.steps.back().x(), map.steps.back().tread_far_x_m);
  // Where the top landing ends at a wall, the wall is a riser of any height standing on it.
  if (const auto wall = end_wall_x_m(map)) {
    p.end_wall = static_cast<int>(p.riser_x.size());
    p.tread_x_hi.back() = *wall;
    p.riser_x.push_back(*wall);
    p.riser_z_lo.push_back(map.steps.back().z());
    p.riser_z_hi.push_back(std::numeric_limits<double>::infinity());
  }
  return p;
}

double outside(double v, double lo, double hi) { return std::max({0.0, lo - v, v - hi}); }

// The model's extent in the x-z profile, `margin` around its first riser, its last tread's far
// end and its lowest and highest levels: points outside lie on steps the model does not have yet.
struct Extent {
  double x_lo, x_hi, z_lo, z_hi;
  double y_lo, y_hi;  // across the stair, the steps' lateral extent widened by the margin
  double next_riser_x, next_riser_z;  // a riser point beyond and above both stands on the top level
  // Boxes in the x-z profile where a level runs unseen for more than a tread before the model's next
  // riser (a landing between two flights seen only at its ends): a riser point in one stands on that
  // level, a step the model does not have yet.
  std::vector<Eigen::Vector4d> unseen;  // x_lo, x_hi, z_lo, z_hi
  Extent(const Profile& p, double margin)
      : x_lo(p.riser_x.front() - margin), x_hi(p.tread_x_hi.back() + margin), z_lo(p.tread_z.front() - margin),
        z_hi(p.tread_z.back() + margin),
        y_lo(p.y_lo - margin),
        y_hi(p.y_hi + margin),
        next_riser_x(p.end_wall >= 0 ? std::numeric_limits<double>::infinity()
                                     : std::max(p.nosing_xz.back().x() + margin, p.top_seen_x - margin)),
        next_riser_z(p.tread_z.back() - margin) {
    for (size_t k = 1; k + 1 < p.tread_z.size() && k < p.riser_x.size(); ++k)
      if (p.riser_x[k] - p.tread_seen_x[k] > p.tread_m)
        unseen.emplace_back(p.tread_seen_x[k] + margin, p.riser_x[k] - margin, p.tread_z[k] - margin,
                            p.tread_z[k + 1] + margin);
  }
  // A plane point: below the top and before the far end, and not before and below the first step;
  // and within the steps' lateral extent: the profile is the flight's, and what lies beside the flight
  // is none of its business (the floor beside an open-sided flight runs on under its treads: seen as a
  // robot's body pitched up at the flight's foot, 170 of 300 tread points disagreed, every registration
  // was rejected for 2.8 s and the model was lost).
  bool holds_plane_point(const Eigen::Vector3d& q) const {
    return q.x() <= x_hi && q.z() <= z_hi && (q.x() >= x_lo || q.z() >= z_lo) && q.y() >= y_lo && q.y() <= y_hi;
  }
  // A riser point standing on the top level where what was seen of it ends, or beyond: the next
  // step's riser, which the model does not have yet (the top tread is taken to run a tread on, and
  // the next riser stands just there, its foot within the model's extent). Where the top level ends
  // at an end wall, the model knows what stands on it.
  bool next_riser(const Eigen::Vector3d& q) const {
    if (q.x() > next_riser_x && q.z() > next_riser_z) return true;
    for (const Eigen::Vector4d& b : unseen)
      if (q.x() > b[0] && q.x() < b[1] && q.z() > b[2] && q.z() < b[3]) return true;
    return false;
  }
  bool holds_nosing(const Eigen::Vector3d& q) const {
    return q.x() >= x_lo && q.x() <= x_hi && q.z() >= z_lo && q.z() <= z_hi;
  }
};

// std::hypot guards against overflow at a cost this inner loop cannot pay.
double norm2(double a, double b) { return std::sqrt(a * a + b * b); }

// Signed residual to the nearest bounded plane, the bounded distance and the face's index.
struct Match {
  double residual = 0.0, distance = std::numeric_limits<double>::infinity();
  int face = -1;
};

// The nearest face of one family: faces at `at` (risers: x; treads: z), each
// spanning [lo, hi] along the other axis; q_at and q_along are the point's.
Match nearest_face(const std::vector<double>& at, const std::vector<double>& lo, const std::vector<double>& hi,
                   double q_at, double q_along) {
  Match m;
  for (size_t k = 0; k < at.size(); ++k) {
    const double r = at[k] - q_at;
    const double d = norm2(r, outside(q_along, lo[k], hi[k]));
    if (d < m.distance) m = {r, d, static_cast<int>(k)};
  }
  return m;
}

Match nearest_riser(const Profile& p, const Eigen::Vector3d& q) {
  return nearest_face(p.riser_x, p.riser_z_lo, p.riser_z_hi, q.x(), q.z());
}

Match nearest_tread(const Profile& p, const Eigen::Vector3d& q) {
  return nearest_face(p.tread_z, p.tread_x_lo, p.tread_x_hi, q.z(), q.x());
}

Eigen::Vector2d nearest_nosing(const Profile& p, const Eigen::Vector3d& q) {
  Eigen::Vector2d best(std::numeric_limits<double>::infinity(), 0.0);
  for (const auto& n : p.nosing_xz) {
    const Eigen::Vector2d r = n - Eigen::Vector2d(q.x(), q.z());
    if (r.norm() < best.norm()) best = r;
  }
  return best;
}

}  // namespace

std::vector<bool> planes_owned_by_steps(const Observation& obs) {
  std::vector<bool> owned(obs.planes.size(), false);
  for (const Step& s : obs.steps)
    for (int k : {s.riser_plane, s.tread_plane})
      if (k >= 0 && k < static_cast<int>(owned.size())) owned[k] = true;
  return owned;
}

// The level the lowest seen step stands on: a horizontal plane no step owns,
// within max_offset_rise_fraction of a rise of where that step's riser begins
// and reaching to within max_gap_m of it along the stair (a table top at that
// height in front of a flight is no floor of it). It is the floor at a
// flight's foot or the tread below, both in the model; the floor reaches
// beyond a tread, and so it tells apart the whole-step shifts that the
// periodic steps cannot.
int foot_plane(const Observation& obs, const RegistrationConfig& c) {
  const Step* lowest = nullptr;
  for (const Step& s : obs.steps)
    if (!lowest || s.nosing_m.z() < lowest->nosing_m.z()) lowest = &s;
  if (!lowest || !lowest->riser_height_m) return -1;  // an inferred rise too: the riser's top or the median
  const double foot_z = lowest->nosing_m.z() - *lowest->riser_height_m;
  // Along the stair, away from the camera: the level reaches the riser's foot from before it
  // (going up) or lies beyond it (going down, its near part hidden by the nosing).
  const double axis = observed_axis_angle_rad(obs).value_or(0.0);
  Eigen::Vector2d u(std::cos(axis), std::sin(axis));
  if (u.dot(lowest->nosing_m.head<2>()) < 0) u = -u;
  const double riser_at = u.dot(lowest->nosing_m.head<2>());
  const std::vector<bool> owned = planes_owned_by_steps(obs);
  int best = -1;
  double best_dz = c.foot_max_offset_rise_fraction * *lowest->riser_height_m;
  for (size_t k = 0; k < obs.planes.size(); ++k) {
    const Plane& p = obs.planes[k];
    if (owned[k] || (p.kind != PlaneKind::Tread && p.kind != PlaneKind::Landing)) continue;
    double reach = -std::numeric_limits<double>::infinity();
    for (const auto& q : p.points) reach = std::max(reach, u.dot(q.head<2>().cast<double>()));  // untrimmed
    if (reach < riser_at - c.foot_max_gap_m) continue;
    const double dz = std::abs(p.centroid.z() - foot_z);
    if (dz < best_dz) best = static_cast<int>(k), best_dz = dz;
  }
  return best;
}

RegistrationInput level_points(const Observation& obs, const RegistrationConfig& c) {
  RegistrationInput in;
  for (const Plane& p : obs.planes)
    if (p.kind == PlaneKind::Tread || p.kind == PlaneKind::Landing) sample(p, c.points_per_plane, in.tread_points);
  return in;
}

RegistrationInput planes_in_view(const Observation& obs, const RegistrationConfig& c) {
  RegistrationInput in = level_points(obs, c);
  for (const Plane& p : obs.planes)
    if (p.kind == PlaneKind::Riser) sample(p, c.points_per_plane, in.riser_points);
  // Nosings seen from above as depth jumps (thesis 3.4.2): going down past a flight's last steps
  // the risers face away, and the last nosing's jump is all that fixes the position along it.
  for (const Edge& e : obs.edges)
    if (e.source == EdgeSource::DepthJump && e.type == EdgeType::Convex)
      in.nosings.push_back(0.5 * (e.start + e.end).cast<double>());
  return in;
}

RegistrationInput registration_input(const Observation& obs, const RegistrationConfig& c) {
  RegistrationInput in;
  for (const Step& s : obs.steps) {
    if (s.riser_plane >= 0 && s.riser_plane < static_cast<int>(obs.planes.size()))
      sample(obs.planes[s.riser_plane], c.points_per_plane, in.riser_points);
    if (s.tread_plane >= 0 && s.tread_plane < static_cast<int>(obs.planes.size()))
      sample(obs.planes[s.tread_plane], c.points_per_plane, in.tread_points);
    in.nosings.push_back(s.nosing_m);
  }
  const int foot = foot_plane(obs, c);
  if (foot >= 0) {
    sample(obs.planes[foot], c.points_per_plane, in.foot_points);
    in.tread_points.insert(in.tread_points.end(), in.foot_points.begin(), in.foot_points.end());
  }
  return in;
}

std::optional<double> observed_axis_angle_rad(const Observation& obs) {
  // Doubled angles average orientations that are only known modulo pi.
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  auto add = [&](double angle, double weight) { sum += weight * Eigen::Vector2d(std::cos(2 * angle), std::sin(2 * angle)); };
  for (const Step& s : obs.steps) {
    if (s.riser_plane >= 0 && s.riser_plane < static_cast<int>(obs.planes.size())) {
      const Plane& p = obs.planes[s.riser_plane];
      if (std::hypot(p.normal.x(), p.normal.y()) > 0.5) add(std::atan2(p.normal.y(), p.normal.x()), p.length_m);
    }
    if (s.tread_plane >= 0 && s.tread_plane < static_cast<int>(obs.planes.size())) {
      // The tread's box edges run across the stair; the axis is perpendicular.
      const Plane& p = obs.planes[s.tread_plane];
      const Eigen::Vector3f across = p.corners[Plane::kTopLeft] - p.corners[Plane::kTopRight] +
                                     p.corners[Plane::kBottomLeft] - p.corners[Plane::kBottomRight];
      if (across.head<2>().norm() > 0.1f) add(std::atan2(across.y(), across.x()) - M_PI / 2, 0.5 * p.length_m);
    }
  }
  if (sum.norm() < 1e-6) return std::nullopt;
  return 0.5 * std::atan2(sum.y(), sum.x());
}

double yaw_from_axis(double axis_angle_rad, double prior_yaw_rad) {
  // yaw maps the axis onto +x: yaw = -axis (+ pi for the opposite sign).
  const double a = wrap_angle(-axis_angle_rad);
  const double b = wrap_angle(a + M_PI);
  return std::abs(wrap_angle(a - prior_yaw_rad)) <= std::abs(wrap_angle(b - prior_yaw_rad)) ? a : b;
}

double foot_agreement_beyond_model(const RegistrationInput& in, const StairMap& map, const Pose4& pose,
                                   const RegistrationConfig& c, const StairPriorConfig& stair) {
  if (map.empty() || in.foot_points.empty()) return 0.0;
  Profile prof = profile(map, stair);
  const Extent extent(prof, c.accept_distance_m);
  const Eigen::Isometry3d T = pose.isometry();
  for (const auto& p : in.riser_points)
    if (extent.holds_plane_point(T * p) && !extent.next_riser(T * p)) return 0.0;
  for (const auto& p : in.nosings)
    if (extent.holds_nosing(T * p)) return 0.0;
  // The top level runs on beyond the part of it seen so far, as the level before the first riser does.
  prof.tread_x_hi.back() = std::numeric_limits<double>::infinity();
  int on = 0;
  for (const auto& p : in.foot_points) on += nearest_tread(prof, T * p).distance < c.accept_distance_m;
  return static_cast<double>(on) / static_cast<double>(in.foot_points.size());
}

double agreeing_points(const Registration& reg, const RegistrationConfig& c) {
  return reg.inliers + c.nosing_weight_points * reg.nosing_inliers;
}

Registration register_to_map(const RegistrationInput& in, const StairMap& map, const Pose4& initial,
                             const RegistrationConfig& c, const StairPriorConfig& stair) {
  Registration reg;
  reg.pose = initial;
  if (map.empty()) return reg;
  const Profile prof = profile(map, stair);
  const Eigen::Matrix3d R = initial.rotation();
  std::vector<Eigen::Vector3d> risers, treads, nosings;
  for (const auto& p : in.riser_points) risers.push_back(R * p);
  for (const auto& p : in.tread_points) treads.push_back(R * p);
  for (const auto& p : in.nosings) nosings.push_back(R * p);
  const double wn = c.nosing_weight_points;

  // The stair repeats itself every step: correspondences wider than a fraction
  // of a tread let the observation slide onto the next step (whole-step shifts
  // are relocalisation's search).
  const double first_thr =
      std::max(c.icp_min_distance_m, std::min(c.icp_max_distance_m, c.icp_max_tread_fraction * typical_tread_m(map, stair)));
  for (double thr = first_thr;; thr = std::max(thr * c.icp_distance_factor, c.icp_min_distance_m)) {
    for (int it = 0; it < c.icp_iterations_per_stage; ++it) {
      const Eigen::Vector3d& t = reg.pose.t_m;
      double sx = 0, wx = 0, sz = 0, wz = 0;
      for (const auto& p : risers) {
        const Match m = nearest_riser(prof, p + t);
        if (m.distance < thr) sx += m.residual, wx += 1;
      }
      for (const auto& p : treads) {
        const Match m = nearest_tread(prof, p + t);
        if (m.distance < thr) sz += m.residual, wz += 1;
      }
      for (const auto& p : nosings) {
        const Eigen::Vector2d r = nearest_nosing(prof, p + t);
        if (r.norm() < thr) sx += wn * r.x(), wx += wn, sz += wn * r.y(), wz += wn;
      }
      if (wx > 0) reg.pose.t_m.x() += sx / wx;
      if (wz > 0) reg.pose.t_m.z() += sz / wz;
    }
    if (thr <= c.icp_min_distance_m) break;
  }

  // Agreement at the final pose, risers and treads apart (a slip that fits the treads must not pass on
  // their majority), over the points within the model's extent: steps beyond its ends are new.
  const Eigen::Vector3d& t = reg.pose.t_m;
  const Extent extent(prof, c.accept_distance_m);
  double sq = 0;
  int riser_in = 0, tread_in = 0, riser_within = 0, tread_within = 0, riser_next = 0;
  auto count = [&](bool held, double d, int& in, int& within) {
    if (d < c.accept_distance_m) ++in, sq += d * d;
    if (held) ++within;
  };
  for (const auto& p : risers) {
    // The next step's riser agrees and disagrees with nothing: an ascent's frame whose only riser
    // in view was the next one (a Kinect v2 under nosings segments few risers) had every
    // registration rejected, and a whole-step search then fitted it onto the top step.
    if (extent.next_riser(p + t)) {
      ++riser_next;
      continue;
    }
    const Match m = nearest_riser(prof, p + t);
    count(extent.holds_plane_point(p + t), m.distance, riser_in, riser_within);
    reg.end_wall_inliers += m.face == prof.end_wall && m.distance < c.accept_distance_m;
  }
  for (const auto& p : treads) count(extent.holds_plane_point(p + t), nearest_tread(prof, p + t).distance, tread_in, tread_within);
  int nosing_in = 0, nosing_within = 0;
  for (const auto& p : nosings) {
    const Eigen::Vector3d q = p + t;
    nosing_in += nearest_nosing(prof, q).norm() < c.accept_distance_m;
    nosing_within += extent.holds_nosing(q);
  }
  reg.x_inliers = riser_in + nosing_in;
  reg.x_within = riser_within + nosing_within;
  reg.nosing_inliers = nosing_in;
  reg.inliers = riser_in + tread_in;
  reg.within = riser_within + tread_within;
  auto ratio = [](int in, int within, size_t all) {
    return all == 0 ? 1.0 : in / std::max({static_cast<double>(within), 0.25 * all, 1.0});
  };
  const double riser_ratio = ratio(riser_in, riser_within, risers.size() - static_cast<size_t>(riser_next));
  const double tread_ratio = ratio(tread_in, tread_within, treads.size());
  reg.inlier_ratio = risers.empty() && treads.empty() ? 0.0 : std::min(riser_ratio, tread_ratio);
  reg.rmse_m = reg.inliers > 0 ? std::sqrt(sq / reg.inliers) : -1.0;
  return reg;
}

}  // namespace stairs
