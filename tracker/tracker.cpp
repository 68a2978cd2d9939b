#include "tracker/tracker.hpp"

#include "tracker/end_wall.hpp"
#include "tracker/merge.hpp"
#include "tracker/model_output.hpp"
#include "tracker/nosing_overhang.hpp"
#include "tracker/prior_links.hpp"
#include "tracker/reconstruction.hpp"
#include "tracker/registration.hpp"
#include "tracker/relocalisation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

namespace stairs {

namespace {

double seconds(int64_t dt_us) { return static_cast<double>(dt_us) * 1e-6; }

// Ascending axis in the gravity-aligned frame: the direction in which the
// observed nosings rise; with one step, the observation's direction decides.
std::optional<double> ascending_yaw(const Observation& obs) {
  const auto axis = observed_axis_angle_rad(obs);
  if (!axis) return std::nullopt;
  const Eigen::Vector2d a(std::cos(*axis), std::sin(*axis));
  double rise = 0.0;
  for (size_t i = 1; i < obs.steps.size(); ++i) {
    const Eigen::Vector3d d = obs.steps[i].nosing_m - obs.steps[i - 1].nosing_m;
    rise += a.dot(d.head<2>()) * d.z();
  }
  if (obs.steps.size() == 1) {
    const double ahead = a.dot(obs.steps[0].nosing_m.head<2>());
    rise = obs.direction == Direction::Down ? -ahead : ahead;
  }
  const double ascending = rise >= 0 ? *axis : *axis + M_PI;
  return wrap_angle(-ascending);
}

}  // namespace

Tracker::Tracker(TrackerConfig config)
    : config_(config),
      direction_(config.direction.window, config.direction.majority),
      odometry_(config.odometry.max_age_s, static_cast<size_t>(std::max(2, config.odometry.max_samples)),
                config.lifecycle.time_jump_back_s) {
  validate(config_);
}

void Tracker::reset() {
  map_ = StairMap();
  direction_.reset();
  accepted_.clear();  // odometry is kept: it is no state of the model
  placed_.reset();
  prior_refuted_ = false;
  height_measured_x_m_ = std::numeric_limits<double>::quiet_NaN();
  have_utime_ = false;
  const StairModel fresh;
  model_ = fresh;
  ++resets_;
}

bool Tracker::seed(const Observation& obs) {
  if (!obs.camera.valid || static_cast<int>(obs.steps.size()) < config_.confirmation.min_seed_steps) return false;
  const auto yaw = ascending_yaw(obs);
  if (!yaw) return false;
  Pose4 pose;
  pose.yaw_rad = *yaw;
  const std::vector<ObservedStep> observed = observed_with_overhang(obs, pose);
  merge(map_, observed, pose, config_.merge, config_.stair, config_.registration.icp_min_distance_m);
  if (map_.empty()) return false;
  note_floor(obs, observed);
  note_registered_on(observed);
  accepted_.push_back({obs.source_utime, pose, to_base_m(obs)});
  x_measured_utime_ = obs.source_utime;
  x_measured_uncertainty_m_ = 0.0;
  speed_change_mps_ = 0.0;
  model_.observations_fused = 1;
  model_.state = TrackingState::Ok;
  model_.registration_rmse_m = -1.0;
  model_.registration_inlier_ratio = 0.0;
  publish(obs, pose, true, 0.0, true);
  return true;
}

void Tracker::note_registered_on(const std::vector<ObservedStep>& observed) {
  if (observed.empty()) return;
  std::vector<double> x;
  for (const ObservedStep& o : observed) x.push_back(o.x());
  registered_on_x_m_ = median(x);
}

// The observation's steps in the model, each riser's overhang measured where its slab is in view.
std::vector<ObservedStep> Tracker::observed_with_overhang(const Observation& obs, const Pose4& pose) const {
  std::vector<ObservedStep> observed = observed_steps(obs, pose);
  for (ObservedStep& o : observed)
    if (o.riser) o.overhang_m = riser_overhang_m(*o.riser, pose.isometry(), o.nosing_m.z(), config_.overhang);
  return observed;
}

bool Tracker::odometry_covers(int64_t utime) const {
  return !accepted_.empty() && odometry_.covers(accepted_.back().utime, utime);
}

Eigen::Vector3d Tracker::to_base_m(const Observation& obs) const {
  if (!config_.mount.configured() || !obs.camera.valid) return Eigen::Vector3d::Zero();
  return obs.camera.gravity_rotation.normalized() * camera_in_base(config_.mount).inverse().translation();
}

// Constant velocity of the point that moves smoothly: with a mount the robot's base (its body pitches
// over a flight's ends and swings the camera forward or back by up to the mount's height), else the
// camera. `to_base_m` is this frame's camera -> base offset (the attitude perception measured).
// The motion starts from where the camera was last placed: the last accepted pose, or a frame
// placed on the planes in view since (a robot slowing as it tipped over a flight's last nosing was
// placed on it for three frames, then the prior from the last registration put it 12 cm on).
Pose4 Tracker::predict(int64_t utime, const Eigen::Vector3d& to_base_m) const {
  const Accepted& a1 = accepted_.back();
  const Pose4& p1 = a1.pose;
  if (const auto p = odometry_.predict(p1, a1.utime, utime)) return *p;
  const Accepted& last = placed_ ? *placed_ : a1;  // accept() clears it
  const Accepted& a0 = accepted_.front();
  // A gap since the position was last measured (registered or placed) predicts no motion; placements
  // on the planes in view carry the velocity on (a robot crossing a top landing towards its end wall).
  if (a1.utime == a0.utime || seconds(utime - last.utime) > config_.motion.max_prediction_s) return last.pose;
  const double dt = seconds(utime - last.utime);
  const double span = seconds(a1.utime - a0.utime);
  const Eigen::Vector3d b1 = a1.base_m(), b0 = a0.base_m(), bl = last.base_m();
  Pose4 p = last.pose;
  p.yaw_rad = wrap_angle(last.pose.yaw_rad + wrap_angle(p1.yaw_rad - a0.pose.yaw_rad) * (dt / span));
  Eigen::Vector3d b = bl + (b1 - b0) * (dt / span);
  // Height follows the stair's mean slope, not the last vertical speed: a gap
  // across a flight's end would carry its slope on.
  b.z() = bl.z() + mean_surface_z_m(map_, b.x(), config_.stair) - mean_surface_z_m(map_, bl.x(), config_.stair);
  p.t_m = b - p.rotation() * to_base_m;
  return p;
}

// The speed along the stair of the point predict() extrapolates, in the first and the second half
// of the velocity window: how much it changed is how far off constant velocity may be per second.
// Halves rather than consecutive poses: the registration noise over one frame interval would
// dominate (3 mm over 33 ms is 0.1 m/s).
void Tracker::note_speed_change() {
  if (accepted_.size() < 3) return;
  const Accepted &a0 = accepted_.front(), &a1 = accepted_.back();
  const double t_mid = 0.5 * seconds(a1.utime - a0.utime);
  const Accepted* mid = &accepted_[1];
  for (size_t k = 1; k + 1 < accepted_.size(); ++k)
    if (std::abs(seconds(accepted_[k].utime - a0.utime) - t_mid) < std::abs(seconds(mid->utime - a0.utime) - t_mid))
      mid = &accepted_[k];
  const double first = (mid->base_m().x() - a0.base_m().x()) / seconds(mid->utime - a0.utime);
  const double second = (a1.base_m().x() - mid->base_m().x()) / seconds(a1.utime - mid->utime);
  speed_change_mps_ = std::abs(second - first);
}

// How far off the prior's position along the stair may be at `utime`, t after it was last measured:
// the speed change seen across the last measured velocity window times t, and what the largest
// plausible acceleration adds since (a robot leaving a flight's last step sped up 7.5 cm past a
// prior whose window had seen its speed change by 2 cm/s). Odometry measures the motion: then none
// (publish() adds what the last registration itself may be off).
double Tracker::prior_x_uncertainty_m(int64_t utime, bool with_odometry) const {
  if (with_odometry) return x_measured_uncertainty_m_;
  const double t = std::max(0.0, seconds(utime - x_measured_utime_));
  return x_measured_uncertainty_m_ + speed_change_mps_ * t + 0.5 * config_.motion.max_accel_mps2 * t * t;
}

// Whether the prior's position along the stair is known to better than half a tread at `utime`: else
// the nearest step to it may be either neighbour, and it tells no whole-step shifts apart.
bool Tracker::prior_tells_steps_apart(int64_t utime, bool with_odometry) const {
  return prior_x_uncertainty_m(utime, with_odometry) < 0.5 * typical_tread_m(map_, config_.stair);
}

// The yaw the observed stair axis gives: near the prior's, or near the last placed pose's. The
// prior turns on at the window's yaw rate, and one frame's axis 10 degrees off (clutter beside a
// flight) gave it one: it turned on 3 degrees a frame, the right axes fell outside the jump around
// it, and the camera was placed 24 cm off with nothing to stop it. Else the prior's yaw.
double Tracker::observed_yaw(double axis_rad, double prior_yaw_rad) const {
  for (const double around : {prior_yaw_rad, (placed_ ? *placed_ : accepted_.back()).pose.yaw_rad})
    if (yaw_off_within_jump(axis_rad, around)) return yaw_from_axis(axis_rad, around);
  return prior_yaw_rad;
}

// How far the yaw an axis gives near `around` lies from it, where motion.max_yaw_jump_deg allows.
std::optional<double> Tracker::yaw_off_within_jump(double axis_rad, double around_rad) const {
  const double off = wrap_angle(yaw_from_axis(axis_rad, around_rad) - around_rad);
  if (std::abs(off) > config_.motion.max_yaw_jump_deg * M_PI / 180.0) return std::nullopt;
  return off;
}

// The yaw the riser planes in view give (a frame without steps: a flight's last risers, the wall
// where its top landing ends), each one within the jump the prior allows of the prior's, averaged by
// width; else the prior's. The prior's, carried on at the last window's yaw rate across a landing,
// turned the far steps away from the camera; a side wall seen while turning on a landing is no
// riser (it is 90 degrees off the prior, which odometry or the last placements give).
double Tracker::yaw_of_risers_in_view(const Observation& obs, double prior_yaw_rad) const {
  double sum = 0.0, weight = 0.0;
  for (const Plane& p : obs.planes) {
    if (p.kind != PlaneKind::Riser || std::hypot(p.normal.x(), p.normal.y()) < 0.5) continue;
    const auto off = yaw_off_within_jump(std::atan2(p.normal.y(), p.normal.x()), prior_yaw_rad);
    if (!off) continue;
    sum += p.length_m * *off;
    weight += p.length_m;
  }
  return weight > 0.0 ? wrap_angle(prior_yaw_rad + sum / weight) : prior_yaw_rad;
}

// One observation, in explicit states: a time jump back restarts the stream;
// an out-of-order observation is dropped; with no model one is seeded; else
// it is tracked (registered and merged, or placed by the motion prior).
const StairModel& Tracker::update(const Observation& obs) {
  const auto start = std::chrono::steady_clock::now();
  const std::string restarted = restart_if_time_went_back(obs.source_utime);
  if (have_utime_ && obs.source_utime <= last_utime_) {
    ++dropped_out_of_order_;
    model_.status = "dropped an out-of-order observation (" + std::to_string(dropped_out_of_order_) + " so far)";
  } else {
    have_utime_ = true;
    last_utime_ = obs.source_utime;
    model_.direction = direction_.update(obs.direction);
    // Odometry that covers the time since the last registration is the prior.
    const bool with_odometry = odometry_covers(obs.source_utime);
    drop_if_lost_long(obs, with_odometry);
    if (map_.empty()) {
      if (!seed(obs)) model_.status = "waiting for a stair to seed the model";
    } else {
      track(obs, with_odometry);
    }
  }
  if (!restarted.empty()) model_.status = model_.status.empty() ? restarted : restarted + "; " + model_.status;
  model_.update_latency_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return model_;
}

std::string Tracker::restart_if_time_went_back(int64_t utime) {
  if (!have_utime_ || seconds(last_utime_ - utime) <= config_.lifecycle.time_jump_back_s) return {};
  // Time went back by more than any reordering: a new stream (a log replayed,
  // a camera restarted). The old model's poses and times mean nothing in it.
  char what[64];
  std::snprintf(what, sizeof what, "time went back %.1f s: model reset", seconds(last_utime_ - utime));
  reset();
  ++time_jumps_;
  return what;
}

// A stair lost for long is dropped once a new one is in view: until then the
// last model stays published. With odometry over the gap it is kept: the
// prior still places it.
void Tracker::drop_if_lost_long(const Observation& obs, bool with_odometry) {
  if (map_.empty() || obs.steps.empty() || with_odometry ||
      seconds(obs.source_utime - accepted_.back().utime) <= config_.lifecycle.reset_after_s)
    return;
  reset();
  model_.direction = direction_.update(obs.direction);
}

// Perception's height over the surface beneath corrects the prior's z (constant velocity would carry
// a flight's slope across a landing), unless it is a riser off: that surface may be the next level.
// Without it the levels in view do: on the model's treads they fix the height wherever along them
// the camera is (x stays the prior's). Frames without steps, placed by the prior, were 2.5 cm off in
// height on average against 0.4 cm for registered ones (randomised walks, tenth session).
Pose4 Tracker::with_observed_height(const Observation& obs, Pose4 pose, bool* measured) const {
  if (measured) *measured = false;
  if (!obs.camera.valid || map_.empty()) return pose;
  const double max_dz = config_.motion.observed_height_max_riser_fraction * typical_riser_m(map_, config_.stair);
  if (obs.camera.height_m) {
    const double z = surface_z_m(map_, pose.t_m.x(), config_.stair) + *obs.camera.height_m;
    if (std::abs(z - pose.t_m.z()) < max_dz) {
      pose.t_m.z() = z;
      if (measured) *measured = true;
    }
    return pose;
  }
  const RegistrationInput levels = level_points(obs, config_.registration);
  if (levels.tread_points.empty()) return pose;
  const Registration reg = register_to_map(levels, map_, pose, config_.registration, config_.stair);
  if (reg.within > 0 && reg.inlier_ratio >= config_.motion.min_inlier_ratio &&
      std::abs(reg.pose.t_m.z() - pose.t_m.z()) < max_dz) {
    pose.t_m.z() = reg.pose.t_m.z();
    if (measured) *measured = true;
  }
  return pose;
}

// A frame in which perception found no staircase may still show the model's risers or nosings:
// from a flight's last steps only one or two are in view. Where they and the levels in view agree
// with the model near the prior, they place the camera (x from them, z from the levels); the
// frame is not merged (perception did not verify it) and does not feed the velocity (a robot's
// jerky climb extrapolated from such poses went a step astray).
std::optional<Registration> Tracker::on_planes_in_view(const Observation& obs, const Pose4& prior,
                                                       bool& height_measured) const {
  height_measured = false;
  const RegistrationInput in = planes_in_view(obs, config_.registration);
  if (in.riser_points.empty() && in.nosings.empty()) return std::nullopt;
  Pose4 start = prior;
  start.yaw_rad = yaw_of_risers_in_view(obs, prior.yaw_rad);
  Registration reg = register_to_map(in, map_, start, config_.registration, config_.stair);
  if (reg.x_inliers == 0 || reg.inlier_ratio < config_.motion.min_inlier_ratio ||
      (reg.pose.t_m - prior.t_m).norm() > config_.motion.max_translation_jump_m)
    return std::nullopt;
  // Agreeing treads and nosings fix the height; faces alone (risers, the end wall) fix only the
  // position along the stair, and the carrier's base then rises by the stair's mean slope over the
  // way they moved it, as predict() carries it. Kept at the prior's height instead, a robot climbing
  // a steep flight slower than its prior, looking up at the top landing's end wall, rose 20 cm
  // above its camera's true height in 2 s.
  const int tread_inliers = reg.inliers - (reg.x_inliers - reg.nosing_inliers);
  height_measured = tread_inliers > 0 || reg.nosing_inliers > 0;
  if (!height_measured) {
    const Eigen::Vector3d to_base = to_base_m(obs);
    const double from_x = start.point_at(to_base).x();
    const double to_x = reg.pose.point_at(to_base).x();
    reg.pose.t_m.z() =
        start.t_m.z() + mean_surface_z_m(map_, to_x, config_.stair) - mean_surface_z_m(map_, from_x, config_.stair);
  }
  return reg;
}

// The camera placed on a registration that is not merged (a frame perception found no staircase in,
// or one the structure check turned down): the next prior starts from it. `uncertainty_m`: how far
// off it may be beyond the registration's own uncertainty.
void Tracker::place(const Observation& obs, const Registration& placed, const std::string& why, double uncertainty_m,
                    bool height_measured) {
  // The end wall alone places it only as well as the wall itself is known.
  const bool wall_only = placed.end_wall_inliers == placed.x_inliers;
  model_.status = why + (wall_only ? "; camera placed on the model's end wall in view"
                                   : "; camera placed on the model's risers or nosings in view");
  placed_ = Accepted{obs.source_utime, placed.pose, to_base_m(obs)};
  prior_refuted_ = false;
  x_measured_utime_ = obs.source_utime;
  x_measured_uncertainty_m_ = uncertainty_m + (wall_only ? map_.end_wall_uncertainty_m.value : 0.0);
  if (!wall_only) note_end_wall(obs, placed.pose, x_measured_uncertainty_m_);
  publish(obs, placed.pose, true, x_measured_uncertainty_m_, height_measured);
}

// Nothing registered: the model's risers, nosings or end wall in view place the
// camera while the prior that finds them is fresh (predict_camera_s since the
// position along the stair was last measured, by a registration or by them: a
// walker crossing the top landing towards its wall, the flight behind it). Else
// the camera stays on the stair by the motion prior (a climber needs its pose
// on every update, e.g. on a landing with no step in view) for predict_camera_s
// after the last registration. Attitude is the observation's own.
void Tracker::place_by_prior(const Observation& obs, const Pose4& prior, bool with_odometry, double since_accept_s,
                             const std::string& why) {
  if (since_accept_s > config_.lifecycle.lost_after_s) model_.state = TrackingState::Lost;
  const double since_measured_s = seconds(obs.source_utime - x_measured_utime_);
  const bool findable = obs.camera.valid && (with_odometry || since_measured_s <= config_.motion.predict_camera_s);
  const bool predicted = obs.camera.valid && (with_odometry || since_accept_s <= config_.motion.predict_camera_s);
  // Odometry measures the carrier's motion, its height's too: a height it carries holds.
  bool height_measured = false;
  if (findable)
    if (const auto placed = on_planes_in_view(obs, prior, height_measured))
      return place(obs, *placed, why, 0.0, height_measured || with_odometry);
  model_.status = !predicted      ? why
                  : with_odometry ? why + "; camera from odometry"
                                  : why + "; camera from the motion prior";
  const Pose4 pose = with_observed_height(obs, prior, &height_measured);
  // A refuted prior (a registration from it that its points disagreed with) is off by more than ICP
  // reaches, by how much unknown: published a tread uncertain (a robot's body rocking 20 cm back was
  // published 2-3 cm uncertain from a prior 20-26 cm off).
  const double carried_m = prior_x_uncertainty_m(obs.source_utime, with_odometry);
  const double uncertainty_m = prior_refuted_ ? std::max(carried_m, typical_tread_m(map_, config_.stair)) : carried_m;
  // A wall first seen from a pose the prior placed (the last riser out of view before the wall came
  // into it) is as good as that pose, and no better: taken while that is within how far a
  // registration may correct the prior (a wall further off could not place the camera anyway).
  if (predicted && uncertainty_m <= config_.motion.max_translation_jump_m) note_end_wall(obs, pose, uncertainty_m);
  publish(obs, pose, predicted, uncertainty_m, height_measured || with_odometry);
}

// `prior_uncertainty_m`: how far the prior may have carried the pose off since it was last measured
// (0: measured); the measurement's own uncertainty is added, as publish() does for the camera.
void Tracker::note_end_wall(const Observation& obs, const Pose4& pose, double prior_uncertainty_m) {
  stairs::note_end_wall(map_, obs, pose, prior_uncertainty_m + config_.registration.position_uncertainty_m,
                        config_.end_wall, config_.stair, config_.merge.max_average_weight,
                        config_.confirmation.min_confirmations);
}

// Whether `pose` is, of the poses a whole number of steps apart along the stair (which a periodic
// flight cannot tell apart), the one nearest `prior`: less than half a step from it along the flight.
bool Tracker::nearest_whole_step_shift(const Pose4& pose, const Pose4& prior) const {
  const Eigen::Vector3d step = typical_step_m(map_, config_.stair);
  return std::abs((pose.t_m - prior.t_m).dot(step.normalized())) < 0.5 * step.norm();
}

void Tracker::track(const Observation& obs, bool with_odometry) {
  const double since_accept_s = seconds(obs.source_utime - accepted_.back().utime);
  const Pose4 prior = predict(obs.source_utime, to_base_m(obs));
  if (!obs.camera.valid || obs.steps.empty()) return place_by_prior(obs, prior, with_odometry, since_accept_s, "observation without steps");

  Pose4 start_pose = prior;
  if (const auto axis = observed_axis_angle_rad(obs)) start_pose.yaw_rad = observed_yaw(*axis, prior.yaw_rad);
  const RegistrationInput input = registration_input(obs, config_.registration);
  // An observation with no plane (nosings only: dark treads seen from above)
  // has nothing to register. Where the constant-velocity prior puts its
  // steps between the model's, merging them duplicated steps (a robot's
  // descent: 8 false model steps); odometry places it well enough.
  if (!with_odometry && input.riser_points.empty() && input.tread_points.empty() &&
      !agrees_where_it_overlaps(map_, observed_steps(obs, start_pose), config_.merge, config_.stair))
    return place_by_prior(obs, prior, with_odometry, since_accept_s,
                          "nosings only, off the model's steps: not merged");
  // Odometry over a gap is a better prior than a whole-step search.
  bool relocalising =
      !with_odometry && (since_accept_s > config_.relocalisation.after_s || model_.state == TrackingState::Lost);
  // How far along the stair a whole-step search may shift the prior: as far as the prior may be off,
  // plus what ICP reaches from a start (a lost stair's prior is stale: every shift).
  const double max_shift_m = model_.state == TrackingState::Lost
                                 ? std::numeric_limits<double>::infinity()
                                 : prior_x_uncertainty_m(obs.source_utime, with_odometry) +
                                       config_.registration.icp_max_tread_fraction * typical_tread_m(map_, config_.stair);
  bool ambiguous = false;
  Registration reg = relocalising ? relocalise(input, map_, start_pose, config_.relocalisation, config_.registration,
                                               config_.stair, max_shift_m, &ambiguous)
                                  : register_to_map(input, map_, start_pose, config_.registration, config_.stair);
  // Both searches below follow a registration from the prior that its points disagree with: the
  // prior is refuted, off by more than ICP reaches (place_by_prior publishes it so).
  // Risers and nosings on the model, none of which agrees: x is the prior's
  // alone, and the prior is off by more than ICP reaches (a robot tipping over
  // a nosing jumps half a step in a frame; the treads then pulled z onto the
  // wrong level for 19 frames). Search as after a gap.
  if (!relocalising && !with_odometry && reg.x_within > 0 && reg.x_inliers == 0) {
    prior_refuted_ = true;
    relocalising = true;
    reg = relocalise(input, map_, start_pose, config_.relocalisation, config_.registration, config_.stair, max_shift_m,
                     &ambiguous);
  } else if (!relocalising && !with_odometry && reg.x_within > 0 && reg.inlier_ratio < config_.motion.min_inlier_ratio) {
    // Fewer points agree than a registration needs: the prior may be off by more than ICP reaches but
    // less than half a step (a robot's body pitching up at a flight's foot swung its camera 14 cm
    // back; the registration stopped 4 cm short with a sixth of its points agreeing, and every later
    // one was turned down until the model was lost). The search's result is taken only where it is
    // that: within half a step of the prior (a hand-held descent's third frame was put a whole step
    // off and the model lost its top step), and no other whole-step shift fits about as well (a tie
    // between two shifts is a guess: a robot on a mid landing took 2 false steps from such guesses).
    prior_refuted_ = true;
    bool tied = true;
    const Registration found = relocalise(input, map_, start_pose, config_.relocalisation, config_.registration,
                                          config_.stair, max_shift_m, &tied);
    if (!tied && nearest_whole_step_shift(found.pose, start_pose)) {
      relocalising = true;
      reg = found;
    }
  }
  if (const auto anchored = on_first_step(obs, input, reg)) {
    reg = *anchored;
    relocalising = true;
    ambiguous = false;  // the flight's first step on the floor seen: no shift fits it alike
  }
  // Whole-step shifts that fit alike (a uniform part of a flight, its ends out of view) are told apart
  // by the prior alone: the one nearest it is taken (a walker's constant speed over a gap; a robot
  // tipping over a nosing, its prior refuted but good to half a tread), unless that is a guess: the
  // stair was lost (the prior is stale), or the prior is both refuted and uncertain by half a tread or
  // more. A robot whose body had rocked 13 cm back while the prior carried it on, turned down for
  // 0.5 s, was placed a whole step up by the shift nearest that prior (a step above the top landing).
  const bool steps_apart = prior_tells_steps_apart(obs.source_utime, with_odometry);
  const bool guessed = ambiguous && (model_.state == TrackingState::Lost || (prior_refuted_ && !steps_apart));
  // Entirely beyond the model (the next flight seen from a landing): nothing
  // to register against, so the motion prior places it while it is fresh.
  // Or only the level it stands on overlaps the model (that landing, its near part seen before):
  // the level fixes the height and nothing the position along the stair. A whole-step search fitted
  // the next flight onto the last one, its copy (4 false model steps on a two-flight walk).
  // Nosings alone fix x and z where perception fitted no plane (a level camera sees a descent's far
  // treads as slivers): registered on them where every one within the model agrees, at least
  // min_seed_steps (one nosing fits any step). Placed by the motion prior instead, a descent's second
  // frame was merged 7 cm off (no velocity after the seed yet), and every later one with it.
  const bool on_nosings = input.riser_points.empty() && input.tread_points.empty() &&
                          reg.x_within >= config_.confirmation.min_seed_steps && reg.x_inliers == reg.x_within;
  if (on_nosings) reg.inlier_ratio = 1.0;
  // With nothing of it on the model, the prior alone says where along the stair its steps go; one
  // uncertain by half a tread or more may put them where a neighbouring step belongs (a hand-held
  // descent's near steps, seen 1.2 s after its far ones with the prior 0.8 m uncertain, were merged
  // 17 cm off: a 1.06 m "landing" inside the flight and 6 false model steps). Not merged, they wait
  // for a frame that also shows the model.
  const bool unplaced = (with_odometry || since_accept_s <= config_.motion.max_prediction_s) &&
                        (reg.within == 0 ? !on_nosings && steps_apart : reg.x_inliers == 0);
  bool height_by_levels = false;  // the levels in view set the height of a frame placed by the prior
  const Pose4 by_prior = unplaced ? with_observed_height(obs, start_pose, &height_by_levels) : start_pose;
  const bool dead_reckoned =
      unplaced && (reg.within == 0 || foot_agreement_beyond_model(input, map_, by_prior, config_.registration,
                                                                  config_.stair) >= config_.motion.min_inlier_ratio);
  // A model its seed alone supports has no velocity to place a frame by: where a step of such a frame
  // lies among the seed's and matches none of them, the two frames disagree, and neither extends the
  // other (a D435 seed 3 m away measured its nosings 9 cm high; the next frame's steps were added
  // beside them and a wrong model grew on both: 5 false steps). The newer frame is no worse
  // evidence: start again from it, as where a registration onto the seed is rejected.
  if (dead_reckoned && !with_odometry && model_.observations_fused <= 1 &&
      !agrees_where_it_overlaps(map_, observed_steps(obs, by_prior), config_.merge, config_.stair)) {
    const std::string why = "its steps disagree with those of a model its seed alone supports";
    if (reseed(obs, why)) return;
    return place_by_prior(obs, prior, with_odometry, since_accept_s, why);
  }
  if (dead_reckoned) {
    reg.pose = by_prior;
    reg.inlier_ratio = 1.0;
  }
  model_.registration_rmse_m = reg.rmse_m;
  model_.registration_inlier_ratio = reg.inlier_ratio;
  // Structure check: the correction must stay within the motion prior's reach
  // (whole-step shifts are relocalisation's business) and most points must agree.
  const double step_m = relocalising ? (config_.relocalisation.step_range + 0.5) * typical_tread_m(map_, config_.stair) : 0.0;
  const double jump = (reg.pose.t_m - start_pose.t_m).norm();
  // After a gap the prior's position along the stair is stale, and a level
  // (the landing the camera stands on) agrees wherever along it the camera is:
  // a relocalisation must rest on risers or nosings (the next flight seen
  // from a mid landing was fitted 0.7 m short, onto the last one).
  const bool x_unknown = relocalising && !dead_reckoned && (reg.x_inliers == 0 || guessed);
  if (x_unknown || reg.inlier_ratio < config_.motion.min_inlier_ratio ||
      jump > config_.motion.max_translation_jump_m + step_m) {
    ++rejected_registrations_;
    const std::string why = guessed     ? std::string("relocalisation rejected: whole-step shifts fit alike and the "
                                                      "prior cannot tell them apart, position along the stair unknown")
                            : x_unknown ? std::string("relocalisation rejected: no riser or nosing agrees, position "
                                                      "along the stair unknown")
                                      : "registration rejected (inliers " + std::to_string(reg.inlier_ratio) +
                                            ", jump " + std::to_string(jump) + " m)";
    if (reseed(obs, why)) return;
    // All but the jump agree, and no other whole-step shift lies nearer the prior: the camera may
    // have moved otherwise than the prior said (a robot's body rocking back over a nosing while the
    // prior carried it on: 12 cm apart; placed by that prior, the next frame started 19 cm off and
    // registered a whole step up). Not merged, as the check asks, but the camera is placed there, as
    // uncertain as the two disagree, and the next frame starts from it: its registration must then
    // agree with it within the prior's reach to be merged.
    if (!relocalising && !x_unknown && reg.x_inliers > 0 && reg.inlier_ratio >= config_.motion.min_inlier_ratio &&
        nearest_whole_step_shift(reg.pose, start_pose))
      return place(obs, reg, why, jump, true);
    place_by_prior(obs, prior, with_odometry, since_accept_s, why);
    return;
  }
  // Registered on the model's steps across a link the prior placed: the frame's steps measure it.
  if (!dead_reckoned) reg = across_prior_links(obs, input, reg);
  accept(obs, reg.pose, !dead_reckoned,
         dead_reckoned ? prior_x_uncertainty_m(obs.source_utime, with_odometry) + config_.registration.position_uncertainty_m
                       : 0.0);
  model_.state = relocalising && !dead_reckoned ? TrackingState::Relocalised : TrackingState::Ok;
  model_.status = dead_reckoned ? "beyond the model: placed by the motion prior" : relocalising ? "relocalised" : "ok";
  publish(obs, reg.pose, true, dead_reckoned ? prior_x_uncertainty_m(obs.source_utime, with_odometry) : 0.0,
          !dead_reckoned || height_by_levels || with_odometry);
}

// Where the registered frame sees steps on both sides of a link the motion prior placed, the part
// beyond it moves by the offset the frame's steps measure, and the frame is registered again on the
// model so corrected; its pose history moves with it (the map moved under the camera, not the
// camera), so the velocity the prior keeps is unchanged. A robot whose body pitched up at a flight's
// foot saw only the next flight for a frame, placed 5.3 cm off by the prior; registered on that
// flight from then on, its camera stayed 5.3 cm off along the first one for 13 s (the step beneath
// it wrong at every nosing).
Registration Tracker::across_prior_links(const Observation& obs, const RegistrationInput& input,
                                         const Registration& reg) {
  if (!any_open_prior_link(map_)) return reg;
  // Outward from the model's first part: each closed link anchors the part beyond it for the next.
  const std::vector<ObservedStep> observed = observed_steps(obs, reg.pose);
  std::optional<StairMap> before;
  // As many steps on each side as a seed needs (one nosing fits any step).
  while (const auto closure =
             measure_prior_link(map_, observed, config_.merge, config_.stair, config_.confirmation.min_seed_steps)) {
    if (!before) before = map_;
    close_prior_link(map_, *closure);
  }
  if (!before) return reg;
  // A correction the frame cannot be registered on is not made.
  const Registration again = register_to_map(input, map_, reg.pose, config_.registration, config_.stair);
  if (again.inlier_ratio < config_.motion.min_inlier_ratio || again.x_inliers == 0) {
    map_ = std::move(*before);
    return reg;
  }
  const Eigen::Vector3d moved = again.pose.t_m - reg.pose.t_m;
  for (Accepted& a : accepted_) a.pose.t_m += moved;
  if (placed_) placed_->pose.t_m += moved;
  return again;
}

// A model only its seed supports is no better evidence than this rejected
// observation (a seed can be a poor frame, and with one pose there is no
// velocity to predict from): start again from the newer one.
bool Tracker::reseed(const Observation& obs, const std::string& why) {
  if (model_.observations_fused > 1 || static_cast<int>(obs.steps.size()) < config_.confirmation.min_seed_steps) return false;
  reset();
  model_.direction = direction_.update(obs.direction);
  if (!seed(obs)) return false;
  model_.status = "reseeded: " + why;
  return true;
}

// Merges a registered observation into the map and keeps the pose history of
// the velocity window.
void Tracker::accept(const Observation& obs, const Pose4& pose, bool x_measured, double prior_link_m) {
  const std::vector<ObservedStep> observed = observed_with_overhang(obs, pose);
  const int inserted = merge(map_, observed, pose, config_.merge, config_.stair, config_.registration.icp_min_distance_m);
  if (x_measured) note_registered_on(observed);
  if (inserted > 0) {
    if (x_measured) extend_prior_links(map_, registered_on_x_m_);
    else open_prior_links(map_, prior_link_m);
  }
  note_floor(obs, observed);
  if (x_measured) note_end_wall(obs, pose, 0.0);
  reconstruct_occluded_steps(map_, config_.reconstruction, config_.stair, config_.confirmation.min_confirmations,
                             config_.merge.max_model_steps);
  accepted_.push_back({obs.source_utime, pose, to_base_m(obs)});
  placed_.reset();
  odometry_.forget_before(obs.source_utime);
  while (accepted_.size() > 2 && seconds(obs.source_utime - accepted_[1].utime) >= config_.motion.velocity_window_s)
    accepted_.pop_front();
  // A dead-reckoned pose continues the prior: neither a measured position nor a speed change.
  if (x_measured) {
    x_measured_utime_ = obs.source_utime;
    x_measured_uncertainty_m_ = 0.0;
    prior_refuted_ = false;
    note_speed_change();
  }
  ++model_.observations_fused;
}

// Every placement starts from a registration, whose position along the stair is known to
// registration.position_uncertainty_m at best: hand-held walks placed the camera 0.1 mm from the right
// place and over the wrong step, a millimetre from a nosing (17 of 78 wrong steps over 99 walks).
void Tracker::publish(const Observation& obs, const Pose4& pose, bool camera_valid, double x_uncertainty_m,
                      bool height_measured) {
  x_uncertainty_m += config_.registration.position_uncertainty_m;
  // A height carried without a mount holds along a flight and along a level, not across where they
  // meet: there the carrier's feet, somewhere behind its camera, climb or stop while the camera's x
  // says otherwise (hand-held climbers reaching a top landing on the end wall alone were published
  // 2-8 cm off its height, a robot's mast camera 10 cm). With a mount the base is what is carried.
  const double base_x = pose.point_at(to_base_m(obs)).x();
  if (height_measured) height_measured_x_m_ = base_x;
  const bool height_known = height_measured || config_.mount.configured() ||
                            (std::isfinite(height_measured_x_m_) &&
                             !reaches_a_flight_end(map_, height_measured_x_m_, base_x, config_.stair));
  // Merged into the map: accepted (seed and accept keep each merged frame's time; times only grow).
  const bool merged = !accepted_.empty() && accepted_.back().utime == obs.source_utime;
  // Relative to the steps the camera was last registered on, the prior's open links are uncertain.
  fill_model(map_, merged, pose, camera_valid, x_uncertainty_m, prior_link_uncertainties_m(map_, registered_on_x_m_),
             obs.camera.gravity_rotation, config_.confirmation, config_.stair, config_.mount,
             flight_overhang_m(map_, config_.overhang),
             model_);
  model_.camera_height_known = model_.camera_beneath_known && height_known;
  model_.base_height_known = model_.base_beneath_known && height_known;
}

// The level the lowest seen step stands on is a floor if it is deeper than any
// tread and no level in view lies below it; one rise below is all a step's own
// rise says (a tread lies there when the steps before it are hidden, and a
// table top beside the flight made it look deep). Only a floor seen under the
// model's first step makes what lies before that step known.
void Tracker::note_floor(const Observation& obs, const std::vector<ObservedStep>& observed) {
  if (map_.empty() || observed.empty()) return;
  for (size_t i = 1; i < map_.steps.size(); ++i) map_.steps[i].on_seen_floor = false;  // a step went in below
  if (!floor_before_lowest_step(obs)) return;
  if (matches(map_, lowest_step(observed), map_.steps.front(), config_.merge, config_.stair))
    map_.steps.front().on_seen_floor = true;
}

bool Tracker::floor_before_lowest_step(const Observation& obs) const {
  const int foot = foot_plane(obs, config_.registration);
  if (foot < 0 || obs.planes[foot].extent_m <= config_.stair.landing_min_depth_m) return false;
  const double below = obs.planes[foot].centroid.z() -
                       config_.registration.foot_max_offset_rise_fraction * typical_riser_m(map_, config_.stair);
  for (const Plane& p : obs.planes)
    if ((p.kind == PlaneKind::Tread || p.kind == PlaneKind::Landing) && p.centroid.z() < below) return false;
  return true;
}

// A flight has one first step. Where the model's stands on a floor seen before it (confirmed) and this
// frame sees the floor before its own lowest step too, the two are that step: a registration that put
// them whole steps apart slid along the flight's periodic risers and nosings, its prior off by nearly a
// step (a robot's camera on a 0.9 m mast swings 20 cm in a frame as the body rocks over a nosing, more
// than the prior's uncertainty lets the whole-step search try; every frame after merged a step low and
// the model grew 2 false steps below its first). Registered again from the prior shifted by those
// steps; kept where it agrees with the model at least as well and brings the two onto each other.
std::optional<Registration> Tracker::on_first_step(const Observation& obs, const RegistrationInput& input,
                                                   const Registration& reg) const {
  if (map_.empty() || obs.steps.empty()) return std::nullopt;
  const MapStep& first = map_.steps.front();
  if (!first.on_seen_floor || first.confirmations < config_.confirmation.min_confirmations ||
      !floor_before_lowest_step(obs))
    return std::nullopt;
  const Eigen::Vector3d step = typical_step_m(map_, config_.stair);
  auto steps_off = [&](const Pose4& pose) {
    const std::vector<ObservedStep> observed = observed_steps(obs, pose);
    const ObservedStep& lowest = lowest_step(observed);
    const long along = std::lround((lowest.x() - first.x()) / step.x()), up = std::lround((lowest.z() - first.z()) / step.z());
    return along == up ? along : 0L;  // whole steps along the flight (else a level, not a step, apart)
  };
  const long k = steps_off(reg.pose);
  if (k == 0 || std::abs(k) > config_.relocalisation.step_range) return std::nullopt;
  Pose4 start = reg.pose;
  start.t_m -= static_cast<double>(k) * step;
  const Registration shifted = register_to_map(input, map_, start, config_.registration, config_.stair);
  if (steps_off(shifted.pose) != 0 || shifted.inlier_ratio < config_.motion.min_inlier_ratio ||
      agreeing_points(shifted, config_.registration) < agreeing_points(reg, config_.registration))
    return std::nullopt;
  return shifted;
}

}  // namespace stairs
