#include "tracker/model_output.hpp"

#include "common/gravity_frame.hpp"
#include "common/limits.hpp"
#include "tracker/config.hpp"
#include "tracker/end_wall.hpp"

#include <cmath>

namespace stairs {

namespace {


Plane box_plane(PlaneKind kind, const Eigen::Vector3d& bottom_left, const Eigen::Vector3d& up, double width_m,
                const std::vector<Eigen::Vector3f>& points, const Eigen::Vector3d& origin) {
  // "Left" is +y, "bottom" the lower edge of a riser or the front edge of a tread.
  Plane p;
  p.kind = kind;
  p.normal = kind == PlaneKind::Riser ? Eigen::Vector3f(-1, 0, 0) : Eigen::Vector3f(0, 0, 1);
  const Eigen::Vector3d right(0.0, -width_m, 0.0);
  p.corners[Plane::kBottomLeft] = bottom_left.cast<float>();
  p.corners[Plane::kBottomRight] = (bottom_left + right).cast<float>();
  p.corners[Plane::kTopLeft] = (bottom_left + up).cast<float>();
  p.corners[Plane::kTopRight] = (bottom_left + up + right).cast<float>();
  p.centroid = (bottom_left + 0.5 * (up + right)).cast<float>();
  p.length_m = static_cast<float>(width_m);
  p.extent_m = static_cast<float>(up.norm());
  p.points.reserve(points.size());
  for (const auto& q : points) p.points.push_back(q - origin.cast<float>());
  return p;
}

// The steps a model publishes: confirmed by min_confirmations observations (or reconstructed between
// such), and none until min_seed_steps are. With the model of the frame merged last (`just_merged`),
// also that frame's steps that continue, step by step, the confirmed steps it saw, where it saw
// min_seed_steps of them (it registered on the flight): a flight's next step comes into view a frame
// before a second frame can confirm it. Such a step says so (its confirmations) and goes again with
// the next frame unless that one sees it too: one odd frame leaves nothing in the model.
std::vector<const MapStep*> published_steps(const StairMap& map, const ConfirmationConfig& c, bool just_merged,
                                            bool& confirmed) {
  const size_t n = map.steps.size();
  std::vector<char> in(n, 0);
  int confirmed_steps = 0, seen_confirmed = 0;
  for (size_t i = 0; i < n; ++i) {
    const MapStep& s = map.steps[i];
    const bool by_count = !s.reconstructed && s.confirmations >= c.min_confirmations;
    confirmed_steps += by_count;
    seen_confirmed += by_count && s.last_merge == map.merges;
    in[i] = s.reconstructed || by_count;
  }
  // One odd frame, or furniture seen once, never makes a model.
  confirmed = confirmed_steps >= c.min_seed_steps;
  if (confirmed && just_merged && seen_confirmed >= c.min_seed_steps) {
    const auto seen_now = [&](size_t i) { return map.steps[i].last_merge == map.merges; };
    const auto continuing = [&](size_t i, size_t next_to) {
      return !in[i] && seen_now(i) && map.steps[i].confirmations >= c.min_confirmations_continuing && in[next_to] &&
             seen_now(next_to);
    };
    for (size_t i = 1; i < n; ++i)
      if (continuing(i, i - 1)) in[i] = 1;  // up the flight
    for (size_t i = n; i-- > 1;)
      if (continuing(i - 1, i)) in[i - 1] = 1;  // down it
  }
  std::vector<const MapStep*> steps;
  if (confirmed)
    for (size_t i = 0; i < n; ++i)
      if (in[i]) steps.push_back(&map.steps[i]);
  return steps;
}

// The step's nosing along x: the tread's edge, a seen riser's face standing the overhang behind it.
double nosing_x_m(const MapStep& s, double overhang_m) { return s.riser_x_m.known() ? s.x() - overhang_m : s.x(); }

// Published step i (relative to `origin`), its riser and tread planes appended to `planes`.
Step model_step(const std::vector<const MapStep*>& steps, size_t i, double first_riser, double tread_typ,
                const Eigen::Vector3d& origin, double camera_y, double overhang_m, const StairPriorConfig& c,
                std::vector<Plane>& planes) {
  const MapStep& s = *steps[i];
  Step out;
  // A rise measured within one frame (tread to tread, no registration in
  // between) is the better figure; the fused heights' difference where no
  // frame measured it.
  double riser = first_riser;
  if (s.riser_height_m.known()) riser = s.riser_height_m.value;
  else if (i > 0) riser = s.z() - steps[i - 1]->z();
  // The tread reaches to the next step's riser; on the last step the model
  // publishes, to the next nosing perception saw in the same frame. Where every
  // view of it was cut (the view's edge, range, the step above hiding its back
  // going down), what was seen is a lower bound: a landing if deeper than any
  // tread, else unknown (a level descent's 24.1 cm tread was published as 18.5 cm).
  const bool last = i + 1 == steps.size();
  const double seen = s.tread_far_x_m - s.x();
  const double tread = !last ? steps[i + 1]->x() - s.x() : s.tread_depth_m.known() ? s.tread_depth_m.value : seen;
  const bool known_tread = !last || s.tread_depth_m.known() || seen > c.landing_min_depth_m;
  const double width = s.y_min_m.known() && s.y_max_m.known() ? s.y_max_m.value - s.y_min_m.value : 0.0;
  const double y_left = s.y_max_m.known() ? s.y_max_m.value : camera_y + 0.5 * width;
  out.riser_height_m = riser;
  if (known_tread) out.tread_depth_m = tread;
  out.landing = known_tread && tread > c.landing_min_depth_m;
  out.width_m = width;
  out.nosing_m = Eigen::Vector3d(nosing_x_m(s, overhang_m), y_left - 0.5 * width, s.z()) - origin;
  out.confirmations = s.confirmations;
  const PlaneSource source = s.reconstructed ? PlaneSource::Reconstructed : PlaneSource::Segmented;
  out.riser_plane = static_cast<int>(planes.size());
  planes.push_back(box_plane(PlaneKind::Riser, Eigen::Vector3d(s.x(), y_left, s.z() - riser) - origin,
                             Eigen::Vector3d(0, 0, riser), width, s.riser_points, origin));
  planes.back().source = source;
  out.tread_plane = static_cast<int>(planes.size());
  planes.push_back(box_plane(out.landing ? PlaneKind::Landing : PlaneKind::Tread,
                             Eigen::Vector3d(s.x(), y_left, s.z()) - origin,
                             Eigen::Vector3d(known_tread ? tread : tread_typ, 0, 0), width, s.tread_points, origin));
  planes.back().source = source;
  return out;
}

// The step beneath a point of the model at x (the last whose nosing lies behind it) and that
// step's tread height (the floor's, 0, before the first).
struct Beneath {
  int step = -1;
  double surface_z_m = 0.0;
};

Beneath beneath(const StairModel& m, double x) {
  Beneath b;
  int k = 0;
  for (const Flight& f : m.flights)
    for (const Step& s : f.steps) {
      if (s.nosing_m.x() > x) return b;
      b = {k++, s.nosing_m.z()};
    }
  return b;
}

// Whether every nosing lies farther than `uncertainty_m` from x along the stair: else the step
// beneath x is a guess between two (a robot's climb placed by constant velocity alone for 0.8 s
// was 7.5 cm behind and one step low, its height a riser off).
// `link_m`: per published step, how far off the motion prior may have placed it relative to the
// steps the camera was registered on (prior_links.hpp), which adds to the uncertainty near it.
bool clear_of_nosings(const StairModel& m, double x, double uncertainty_m, const std::vector<double>& link_m) {
  size_t k = 0;
  for (const Flight& f : m.flights)
    for (const Step& s : f.steps)
      if (std::abs(s.nosing_m.x() - x) <= uncertainty_m + link_m[k++]) return false;
  return true;
}

// Whether x lies over the part of the stair the model has seen: before the
// first riser only where the level it stands on was seen as a floor (a tread
// seen one rise below is no floor: a flight whose first steps were hidden put a
// hand-held camera 35 cm low over a "floor" that was the second tread).
// Beyond the last step it reaches as far as its tread was seen, or to the wall where it ends.
bool over_seen_part(const MapStep& first, double seen_to_x, const Eigen::Vector3d& origin, double x) {
  return x <= seen_to_x - origin.x() && (first.on_seen_floor || x >= first.x() - origin.x());
}

// The camera in the model: its pose, the step beneath and its height over that step's tread;
// known only over the part of the stair the model has seen.
void place_camera(const Pose4& camera, const Eigen::Quaterniond& gravity_rotation, const Eigen::Vector3d& origin,
                  const MapStep& first, double seen_to_x, double x_uncertainty_m, const std::vector<double>& link_m,
                  StairModel& out) {
  const Eigen::Vector3d cam = camera.t_m - origin;
  out.camera_position_m = cam;
  out.camera_orientation = Eigen::Quaterniond(camera.rotation()) * gravity_rotation;
  out.camera_orientation.normalize();
  const Beneath b = beneath(out, cam.x());
  out.camera_step_index = b.step;
  out.camera_height_m = cam.z() - b.surface_z_m;
  out.camera_beneath_known =
      over_seen_part(first, seen_to_x, origin, cam.x()) && clear_of_nosings(out, cam.x(), x_uncertainty_m, link_m);
}

// The carrier's base from the placed camera and the mount (common/mount.hpp base_of_camera).
void place_base(const MountConfig& mount, const Eigen::Vector3d& origin, const MapStep& first, double seen_to_x,
                double x_uncertainty_m, const std::vector<double>& link_m, StairModel& out) {
  out.base_valid = out.camera_valid && mount.configured();
  if (!out.base_valid) return;
  const Eigen::Isometry3d base = base_of_camera(out.camera_position_m, out.camera_orientation, mount);
  out.base_position_m = base.translation();
  out.base_orientation = Eigen::Quaterniond(base.linear()).normalized();
  const Beneath b = beneath(out, out.base_position_m.x());
  out.base_step_index = b.step;
  out.base_height_m = out.base_position_m.z() - b.surface_z_m;
  out.base_beneath_known = over_seen_part(first, seen_to_x, origin, out.base_position_m.x()) &&
                           clear_of_nosings(out, out.base_position_m.x(), x_uncertainty_m, link_m);
}

}  // namespace

void fill_model(const StairMap& map, bool just_merged, const Pose4& camera, bool camera_valid, double x_uncertainty_m,
                const std::vector<double>& link_m, const Eigen::Quaterniond& gravity_rotation, const ConfirmationConfig& c,
                const StairPriorConfig& stair, const MountConfig& mount, double overhang_m, StairModel& out) {
  out.flights.clear();
  out.planes.clear();
  const std::vector<const MapStep*> steps = published_steps(map, c, just_merged, out.confirmed);
  out.camera_valid = camera_valid && !steps.empty();
  out.camera_step_index = out.base_step_index = -1;
  out.camera_height_m = out.base_height_m = 0.0;
  out.camera_beneath_known = out.base_beneath_known = out.base_valid = false;
  out.camera_position_uncertainty_m = out.camera_valid ? x_uncertainty_m : -1.0;
  if (steps.empty()) return;
  std::vector<double> published_link_m;
  for (const MapStep* s : steps)
    published_link_m.push_back(link_m.empty() ? 0.0 : link_m[static_cast<size_t>(s - map.steps.data())]);
  // Along the stair from the model's origin, its first step's.
  if (out.camera_valid) out.camera_position_uncertainty_m += published_link_m.front();

  const MapStep& first = *steps.front();
  const double first_riser = first.riser_height_m.known() ? first.riser_height_m.value : typical_riser_m(map, stair);
  const double y_mid = first.y_min_m.known() && first.y_max_m.known()
                           ? 0.5 * (first.y_min_m.value + first.y_max_m.value)
                           : camera.t_m.y();
  // Beneath the first nosing, as the model's first step's nosing lies at x = 0 (../shared/DESIGN.md).
  const Eigen::Vector3d origin(nosing_x_m(first, overhang_m), y_mid, first.z() - first_riser);
  const double tread_typ = typical_tread_m(map, stair);
  Flight flight;
  for (size_t i = 0; i < steps.size(); ++i) {
    const Step step = model_step(steps, i, first_riser, tread_typ, origin, camera.t_m.y(), overhang_m, stair, out.planes);
    flight.width_m = std::max(flight.width_m, step.width_m);
    flight.steps.push_back(step);
    // A landing ends its flight unless it is the top of the model.
    if (step.landing && i + 1 < steps.size() && out.flights.size() + 1 < static_cast<size_t>(limits::kModelFlights)) {
      out.flights.push_back(std::move(flight));
      flight = Flight();
    }
  }
  out.flights.push_back(std::move(flight));
  const MapStep& last = *steps.back();
  double seen_to_x = std::max(last.x(), last.tread_far_x_m);
  if (const auto wall = end_wall_x_m(map); wall && &last == &map.steps.back()) seen_to_x = std::max(seen_to_x, *wall);
  place_camera(camera, gravity_rotation, origin, first, seen_to_x, x_uncertainty_m, published_link_m, out);
  place_base(mount, origin, first, seen_to_x, x_uncertainty_m, published_link_m, out);
}

std::vector<Step> steps_from_camera(const StairModel& model) {
  std::vector<Step> out;
  if (!model.camera_valid) return out;
  const Eigen::Isometry3d to_camera =
      gravity_frame_pose(model.camera_position_m, model.camera_orientation).inverse();
  for (const Flight& f : model.flights)
    for (Step s : f.steps) {
      s.nosing_m = to_camera * s.nosing_m;
      s.riser_plane = s.tread_plane = -1;  // the model's planes are not carried along
      out.push_back(s);
    }
  return out;
}

}  // namespace stairs
