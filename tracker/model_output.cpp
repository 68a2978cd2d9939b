#include "tracker/model_output.hpp"

#include "common/gravity_frame.hpp"
#include "tracker/config.hpp"

#include <cmath>

namespace stairs {

namespace {

constexpr size_t kMaxFlights = 16;  // stair_model_t.MAX_FLIGHTS

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

}  // namespace

void fill_model(const StairMap& map, const Pose4& camera, bool camera_valid,
                const Eigen::Quaterniond& gravity_rotation, const TrackerConfig& c, StairModel& out) {
  out.flights.clear();
  out.planes.clear();
  std::vector<const MapStep*> steps;
  int confirmed = 0;
  for (const auto& s : map.steps) {
    confirmed += !s.reconstructed && s.confirmations >= c.min_confirmations;
    if (s.reconstructed || s.confirmations >= c.min_confirmations) steps.push_back(&s);
  }
  // A stair is published only once enough observations agree on enough of its
  // steps: one odd frame, or furniture seen once, never makes a model.
  out.confirmed = confirmed >= c.min_seed_steps;
  if (!out.confirmed) steps.clear();
  out.camera_valid = camera_valid && !steps.empty();
  out.camera_step_index = -1;
  out.camera_height_m = 0.0;
  out.camera_beneath_known = false;
  if (steps.empty()) return;

  const double tread_typ = typical_tread_m(map, c);
  const double riser_typ = typical_riser_m(map, c);
  const MapStep& first = *steps.front();
  const double first_riser = first.riser_height_m.known() ? first.riser_height_m.value : riser_typ;
  const double y_mid = first.y_min_m.known() && first.y_max_m.known()
                           ? 0.5 * (first.y_min_m.value + first.y_max_m.value)
                           : camera.t_m.y();
  const Eigen::Vector3d origin(first.x(), y_mid, first.z() - first_riser);

  Flight flight;
  std::vector<double> step_x, step_z;  // stair frame, for the camera lookup
  for (size_t i = 0; i < steps.size(); ++i) {
    const MapStep& s = *steps[i];
    Step out_step;
    // A rise measured within one frame (tread to tread, no registration in
    // between) is the better figure; the fused heights' difference where
    // no frame measured it.
    double riser = first_riser;
    if (s.riser_height_m.known()) riser = s.riser_height_m.value;
    else if (i > 0) riser = s.z() - steps[i - 1]->z();
    const double far = i + 1 < steps.size() ? steps[i + 1]->x() : s.tread_far_x_m;
    const double tread = far - s.x();
    const bool known_tread = i + 1 < steps.size() || s.tread_far_x_m > s.x();
    const double width = s.y_min_m.known() && s.y_max_m.known() ? s.y_max_m.value - s.y_min_m.value : 0.0;
    const double y_left = s.y_max_m.known() ? s.y_max_m.value : camera.t_m.y() + 0.5 * width;
    out_step.riser_height_m = riser;
    if (known_tread) out_step.tread_depth_m = tread;
    out_step.landing = known_tread && tread > c.landing_min_depth_m;
    out_step.width_m = width;
    out_step.nosing_m = Eigen::Vector3d(s.x(), y_left - 0.5 * width, s.z()) - origin;
    out_step.confirmations = s.confirmations;
    const PlaneSource source = s.reconstructed ? PlaneSource::Reconstructed : PlaneSource::Segmented;
    out_step.riser_plane = static_cast<int>(out.planes.size());
    out.planes.push_back(box_plane(PlaneKind::Riser, Eigen::Vector3d(s.x(), y_left, s.z() - riser) - origin,
                                   Eigen::Vector3d(0, 0, riser), width, s.riser_points, origin));
    out.planes.back().source = source;
    out_step.tread_plane = static_cast<int>(out.planes.size());
    out.planes.push_back(box_plane(out_step.landing ? PlaneKind::Landing : PlaneKind::Tread,
                                   Eigen::Vector3d(s.x(), y_left, s.z()) - origin,
                                   Eigen::Vector3d(known_tread ? tread : tread_typ, 0, 0), width, s.tread_points,
                                   origin));
    out.planes.back().source = source;
    flight.width_m = std::max(flight.width_m, width);
    flight.steps.push_back(out_step);
    step_x.push_back(out_step.nosing_m.x());
    step_z.push_back(out_step.nosing_m.z());
    // A landing ends its flight unless it is the top of the model.
    if (out_step.landing && i + 1 < steps.size() && out.flights.size() + 1 < kMaxFlights) {
      out.flights.push_back(std::move(flight));
      flight = Flight();
    }
  }
  out.flights.push_back(std::move(flight));

  const Eigen::Vector3d cam = camera.t_m - origin;
  out.camera_position_m = cam;
  out.camera_orientation = Eigen::Quaterniond(camera.rotation()) * gravity_rotation;
  out.camera_orientation.normalize();
  // The step beneath the camera: the last whose riser lies behind it.
  int k = -1;
  while (k + 1 < static_cast<int>(step_x.size()) && step_x[k + 1] <= cam.x()) ++k;
  out.camera_step_index = k;
  out.camera_height_m = cam.z() - (k < 0 ? 0.0 : step_z[k]);
  // Beyond the last step's seen tread the model knows nothing of the surface.
  const MapStep& last = *steps.back();
  out.camera_beneath_known = cam.x() <= std::max(last.x(), last.tread_far_x_m) - origin.x();
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
