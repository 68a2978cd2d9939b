#include "drivers/sim/trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace stairs::sim {
namespace {

constexpr double kRad = M_PI / 180.0;

double wave(double amplitude, double hz, double phase, double t) {
  return amplitude * std::sin(2.0 * M_PI * hz * t + phase);
}

// Where the stair starts and ends along x: first riser, top nosing of the last
// flight, and the goings of the first and the last regular step.
struct Extent {
  double bottom_x = 0.0, top_x = 0.0, first_tread = 0.3, last_tread = 0.3;
};

Extent extent(const Scene& s) {
  Extent e;
  const std::vector<StepGeometry> steps = step_geometry(s);
  if (steps.empty()) {
    e.top_x = s.kind == SceneKind::Ramp ? s.ramp_length_m : 0.0;
    return e;
  }
  e.bottom_x = steps.front().riser_x_m;
  e.top_x = steps.back().riser_x_m - s.nosing_m;
  if (steps.size() > 1) {
    e.first_tread = steps.front().end_x_m - steps.front().riser_x_m;
    e.last_tread = steps[steps.size() - 2].end_x_m - steps[steps.size() - 2].riser_x_m;
  }
  return e;
}

}  // namespace

Eigen::Isometry3d camera_pose(const Eigen::Vector3d& position_m, double yaw_deg, double pitch_deg, double roll_deg) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = optical_rotation(yaw_deg, pitch_deg, roll_deg);
  T.translation() = position_m;
  return T;
}

Eigen::Isometry3d base_pose(const Eigen::Vector3d& position_m, double yaw_deg, double pitch_deg, double roll_deg) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  // Nose up is a negative turn about the base's y (left) axis.
  T.linear() = (Eigen::AngleAxisd(yaw_deg * kRad, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(-pitch_deg * kRad, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(roll_deg * kRad, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  T.translation() = position_m;
  return T;
}

MountConfig TrajectoryConfig::mount() const {
  MountConfig m;
  if (carrier != Carrier::Robot) return m;
  m.height_m = static_cast<float>(height_m);
  m.pitch_deg = static_cast<float>(pitch_deg);
  return m;
}

TrajectoryConfig trajectory_defaults(Carrier carrier) {
  TrajectoryConfig c;
  c.carrier = carrier;
  if (carrier == Carrier::Robot) {
    c.height_m = 0.45;
    c.pitch_deg = -20.0;
    c.speed_mps = 0.3;
  }
  return c;
}

Situation situation_from_name(const std::string& n) {
  if (n == "approach") return Situation::Approach;
  if (n == "first_step") return Situation::FirstStep;
  if (n == "flight") return Situation::Flight;
  if (n == "landing") return Situation::Landing;
  if (n == "full") return Situation::Full;
  if (n == "round_trip") return Situation::RoundTrip;
  throw std::invalid_argument("unknown situation '" + n + "' (approach, first_step, flight, landing, full, round_trip)");
}

Carrier carrier_from_name(const std::string& n) {
  if (n == "handheld") return Carrier::HandHeld;
  if (n == "robot") return Carrier::Robot;
  throw std::invalid_argument("unknown carrier '" + n + "' (handheld, robot)");
}

std::string situation_name(Situation s) {
  switch (s) {
    case Situation::Approach: return "approach";
    case Situation::FirstStep: return "first_step";
    case Situation::Flight: return "flight";
    case Situation::Landing: return "landing";
    case Situation::Full: return "full";
    case Situation::RoundTrip: return "round_trip";
  }
  return "?";
}

std::string carrier_name(Carrier c) { return c == Carrier::Robot ? "robot" : "handheld"; }

Trajectory::Trajectory(const Scene& scene, const TrajectoryConfig& c) : scene_(scene), config_(c) {
  if (!(c.speed_mps > 0.0) || !(c.fps > 0.0)) throw std::invalid_argument("trajectory: speed and fps must be positive");
  const Extent e = extent(scene);
  const double lo = scene_start_x_m(scene) + 0.3;
  const double hi = scene.walk_end_m > 0 ? std::min(scene.walk_end_m, scene_end_x_m(scene) - 0.4)
                                         : scene_end_x_m(scene) - 0.4;
  const bool stairs = !step_geometry(scene).empty();
  Situation sit = stairs ? c.situation : Situation::Full;
  if (!c.descending) {
    switch (sit) {
      case Situation::Approach: x0_ = e.bottom_x - c.approach_m, x1_ = e.bottom_x - 0.5; break;
      case Situation::FirstStep: x0_ = e.bottom_x - 0.6, x1_ = e.bottom_x + e.first_tread + 0.1; break;
      case Situation::Flight: x0_ = e.bottom_x, x1_ = e.top_x; break;
      case Situation::Landing: x0_ = e.top_x - 2.0 * e.last_tread, x1_ = e.top_x + 1.2; break;
      case Situation::Full: x0_ = e.bottom_x - c.approach_m, x1_ = hi; break;
      case Situation::RoundTrip: x0_ = e.bottom_x - c.approach_m, x1_ = e.top_x + 0.8; break;
    }
  } else {
    switch (sit) {
      case Situation::Approach: x0_ = e.top_x + c.approach_m, x1_ = e.top_x + 0.5; break;
      case Situation::FirstStep: x0_ = e.top_x + 0.6, x1_ = e.top_x - e.last_tread - 0.1; break;
      case Situation::Flight: x0_ = e.top_x, x1_ = e.bottom_x; break;
      case Situation::Landing: x0_ = e.bottom_x + 2.0 * e.first_tread, x1_ = e.bottom_x - 1.2; break;
      case Situation::Full: x0_ = e.top_x + c.approach_m, x1_ = e.bottom_x - c.approach_m; break;
      case Situation::RoundTrip: x0_ = e.top_x + c.approach_m, x1_ = e.bottom_x - 0.8; break;
    }
  }
  x0_ = std::clamp(x0_, lo, hi);
  x1_ = std::clamp(x1_, lo, hi);
  if (sit == Situation::RoundTrip && !(c.turn_s > 0.0)) throw std::invalid_argument("trajectory: turn_s must be positive");
  const double duration_s = sit == Situation::RoundTrip ? 2.0 * leg_s() + c.turn_s : leg_s();
  round_trip_ = sit == Situation::RoundTrip;
  frames_ = 1 + static_cast<int>(std::floor(duration_s * c.fps));
}

double Trajectory::leg_s() const { return std::abs(x1_ - x0_) / config_.speed_mps; }

Trajectory::PathPoint Trajectory::path_at(double t) const {
  const double dir = x1_ >= x0_ ? 1.0 : -1.0;
  const double heading = (config_.descending ? 180.0 : 0.0) + config_.yaw_deg;
  const auto along = [&](double from, double sense, double dt) {
    return std::clamp(from + sense * config_.speed_mps * dt, std::min(x0_, x1_), std::max(x0_, x1_));
  };
  if (!round_trip_ || t <= leg_s()) return {along(x0_, dir, t), heading, dir};
  if (t < leg_s() + config_.turn_s) return {x1_, heading + 180.0 * (t - leg_s()) / config_.turn_s, 0.0};
  return {along(x1_, -dir, t - leg_s() - config_.turn_s), heading + 180.0, -dir};
}

double Trajectory::smoothed_surface_m(double x, double y) const {
  // A walker's head and a tracked robot's body both follow the stair's mean
  // slope, not each step: average the surface over +-0.35 m.
  constexpr int kSamples = 15;
  constexpr double kHalf = 0.35;
  double sum = 0.0;
  for (int i = 0; i < kSamples; ++i)
    sum += surface_height_m(scene_, x + kHalf * (2.0 * i / (kSamples - 1) - 1.0), y);
  return sum / kSamples;
}

Eigen::Isometry3d Trajectory::pose_at(double t) const {
  const TrajectoryConfig& c = config_;
  const PathPoint at = path_at(t);
  const double x = at.x_m;
  double y = c.lateral_m;
  double z = smoothed_surface_m(x, y) + c.height_m;
  double yaw = at.heading_deg;
  double pitch = c.pitch_deg, roll = c.roll_deg;
  const double w = c.wobble;
  if (c.carrier == Carrier::HandHeld) {
    // Gait: bounce at the step frequency, sway, and a slowly wandering hand.
    z += wave(0.015 * w, 1.8, 0.0, t);
    y += wave(0.02 * w, 0.9, 0.5, t);
    pitch += wave(2.5 * w, 0.5, 0.3, t);
    roll += wave(2.0 * w, 0.9, 1.1, t);
    yaw += wave(1.5 * w, 0.35, 2.0, t);
  } else {
    // A rigid body: the base stands on the smoothed surface and pitches with its slope along the
    // heading; the camera sits on it at the mount's height and pitch, so on a slope it is carried
    // back and up the body's tilted axis, not straight up (issue 15: outputs in the base frame).
    const double heading = std::cos(yaw * kRad) >= 0 ? 1.0 : -1.0;
    const double slope = (smoothed_surface_m(x + 0.05 * heading, y) - smoothed_surface_m(x - 0.05 * heading, y)) / 0.1;
    const double body_pitch = std::atan(slope) / kRad + wave(0.3 * w, 3.0, 0.0, t);
    const double body_roll = wave(0.3 * w, 2.3, 0.7, t);
    return base_pose({x, y, smoothed_surface_m(x, y)}, yaw, body_pitch, body_roll) * camera_in_base(c.mount());
  }
  return camera_pose({x, y, z}, yaw, pitch, roll);
}

}  // namespace stairs::sim
