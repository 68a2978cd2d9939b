// Camera trajectories through a scene for the thesis' four situations
// (approaching the first step, traversing the first step, traversing the
// flight, landing), ascending or descending, hand-held or robot-mounted; and
// a round trip: up (or down) the whole stair, a turn on the spot on the far
// landing, and back the same way (issue 15: turning around on a landing).
#pragma once

#include "common/mount.hpp"
#include "drivers/sim/scene.hpp"

#include <Eigen/Geometry>

#include <string>
#include <vector>

namespace stairs::sim {

// Optical frame of a camera at `position_m` (stair frame) heading yaw_deg
// from +x (counter-clockwise seen from above), its optical axis pitch_deg
// above the horizon, turned roll_deg about the optical axis (positive = right
// side down).
Eigen::Isometry3d camera_pose(const Eigen::Vector3d& position_m, double yaw_deg, double pitch_deg, double roll_deg);

// A robot's base frame (REP 103: x forward, y left, z up) at `position_m`, heading yaw_deg from +x,
// nose pitch_deg up, rolled roll_deg about its x axis (positive = right side down).
Eigen::Isometry3d base_pose(const Eigen::Vector3d& position_m, double yaw_deg, double pitch_deg, double roll_deg);

enum class Carrier { HandHeld, Robot };
enum class Situation { Approach, FirstStep, Flight, Landing, Full, RoundTrip };

struct TrajectoryConfig {
  Carrier carrier = Carrier::HandHeld;
  Situation situation = Situation::Full;
  bool descending = false;
  double speed_mps = 0.6;   // horizontal speed along the path
  double fps = 30.0;        // frames per second
  double height_m = 1.0;    // hand-held: camera above the (smoothed) surface beneath; robot: up the base's z axis
  double pitch_deg = -35.0; // hand-held: below the horizon; robot: mount pitch relative to the body
  double lateral_m = 0.0;   // offset from the flight's centre line, + = left
  double yaw_deg = 0.0;     // heading offset from straight up (or down) the stair
  double roll_deg = 0.0;    // hand-held: the hand's roll about the optical axis (+ = right side down), under the wobble
  double wobble = 1.0;      // scale of the gait wobble / robot vibration, 0 = steady
  double approach_m = 3.0;  // distance to the first edge where Approach and Full begin
  double turn_s = 4.0;      // round trip: seconds for the half turn on the spot (45 deg/s)

  // The robot's mount (height_m, pitch_deg on the base), as the config file's "mount" object
  // gives it to perception and the tracker; none for a hand-held camera.
  MountConfig mount() const;
};

// Defaults of a carrier: hand-held 1.0 m high, pitch -35 deg; robot: camera 0.45 m up the
// base's z axis, pitched -20 deg on a rigid body whose base stands on the smoothed surface and
// pitches with its slope.
TrajectoryConfig trajectory_defaults(Carrier carrier);

Situation situation_from_name(const std::string& name);  // approach, first_step, flight, landing, full, round_trip
Carrier carrier_from_name(const std::string& name);      // handheld, robot
std::string situation_name(Situation s);
std::string carrier_name(Carrier c);

class Trajectory {
 public:
  Trajectory(const Scene& scene, const TrajectoryConfig& config);

  int frames() const { return frames_; }
  double time_s(int frame) const { return frame / config_.fps; }
  Eigen::Isometry3d pose(int frame) const { return pose_at(time_s(frame)); }
  Eigen::Isometry3d pose_at(double t_s) const;

  double start_x_m() const { return x0_; }  // path along x, camera centre
  double end_x_m() const { return x1_; }

 private:
  double smoothed_surface_m(double x, double y) const;
  // Along-x position, heading (deg from +x) and the sense of travel at t.
  struct PathPoint {
    double x_m, heading_deg, travel;  // travel: +1 along +x, -1 along -x, 0 turning on the spot
  };
  PathPoint path_at(double t_s) const;
  double leg_s() const;  // one way of the path, walking

  Scene scene_;
  TrajectoryConfig config_;
  double x0_ = 0.0, x1_ = 0.0;
  int frames_ = 0;
  bool round_trip_ = false;
};

}  // namespace stairs::sim
