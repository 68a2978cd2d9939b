// The incremental stair model fused over observations (thesis chapter 5),
// tracked at walking speed: seed, predict (constant velocity, height along the
// stair's mean slope), register (4-DoF, re-localising after gaps), merge,
// reconstruct, publish in the stair frame.
#pragma once

#include "common/types.hpp"
#include "tracker/config.hpp"
#include "tracker/direction.hpp"
#include "tracker/merge.hpp"
#include "tracker/odometry_prior.hpp"
#include "tracker/pose.hpp"
#include "tracker/registration.hpp"
#include "tracker/stair_map.hpp"

#include <deque>
#include <limits>
#include <optional>
#include <string>

namespace stairs {

class Tracker {
 public:
  explicit Tracker(TrackerConfig config = {});
  // Fuses one observation; observations older than the last one are dropped
  // (counted) and leave the model unchanged, unless time went back by more
  // than time_jump_back_s: then a new stream begins and the model is reset.
  const StairModel& update(const Observation& obs);
  // Optional odometry (DESIGN.md odometry.txt, STAIRS_ODOMETRY): where it
  // covers the time since the last registration it is the motion prior, the
  // camera stays valid and the model is kept however long no stair is in view.
  void add_odometry(const OdometrySample& o) { odometry_.add(o); }
  const StairModel& model() const { return model_; }
  void reset();

  int64_t dropped_out_of_order() const { return dropped_out_of_order_; }
  int64_t rejected_registrations() const { return rejected_registrations_; }
  int64_t resets() const { return resets_; }
  int64_t time_jumps() const { return time_jumps_; }  // resets because time went back
  int64_t dropped_odometry() const { return odometry_.dropped(); }

 private:
  bool seed(const Observation& obs);
  std::string restart_if_time_went_back(int64_t utime);
  void drop_if_lost_long(const Observation& obs, bool with_odometry);
  void track(const Observation& obs, bool with_odometry);
  // height_measured: the pose's height was measured (levels or nosings agreed), not carried along the
  // stair's mean slope by faces alone.
  void place(const Observation& obs, const Registration& placed, const std::string& why, double uncertainty_m,
             bool height_measured);
  bool nearest_whole_step_shift(const Pose4& pose, const Pose4& prior) const;
  void place_by_prior(const Observation& obs, const Pose4& prior, bool with_odometry, double since_accept_s,
                      const std::string& why);
  bool reseed(const Observation& obs, const std::string& why);
  // x_measured: the pose was registered on the model (not carried on by the prior).
  // prior_link_m: where the prior placed it (x_measured false), how far off its new steps may lie from
  // the model's next to them (prior_links.hpp).
  void accept(const Observation& obs, const Pose4& pose, bool x_measured, double prior_link_m);
  // `reg` with the links to steps the prior placed that its frame sees across measured and closed.
  Registration across_prior_links(const Observation& obs, const RegistrationInput& input, const Registration& reg);
  // Where the steps of a frame seeded or registered on the model lie (registered_on_x_m_).
  void note_registered_on(const std::vector<ObservedStep>& observed);
  // Marks the model's first step as standing on a seen floor (tracker.cpp).
  void note_floor(const Observation& obs, const std::vector<ObservedStep>& observed);
  // Whether the observation sees a floor before its lowest step (deeper than any tread, nothing below).
  bool floor_before_lowest_step(const Observation& obs) const;
  // `reg` redone from whole steps off, where it puts the observation's first step off the model's.
  std::optional<Registration> on_first_step(const Observation& obs, const RegistrationInput& input,
                                            const Registration& reg) const;
  // The end wall in view (end_wall.hpp), seen from `pose`, which the prior may have carried this far off.
  void note_end_wall(const Observation& obs, const Pose4& pose, double prior_uncertainty_m);
  // `measured` (when given): whether the levels in view or perception's height set the height.
  Pose4 with_observed_height(const Observation& obs, Pose4 pose, bool* measured = nullptr) const;
  // `height_measured`: whether levels or nosings in view fixed the height (else faces alone carried it).
  std::optional<Registration> on_planes_in_view(const Observation& obs, const Pose4& prior,
                                                bool& height_measured) const;
  Pose4 predict(int64_t utime, const Eigen::Vector3d& to_base_m) const;
  double observed_yaw(double axis_rad, double prior_yaw_rad) const;
  std::optional<double> yaw_off_within_jump(double axis_rad, double around_rad) const;
  double yaw_of_risers_in_view(const Observation& obs, double prior_yaw_rad) const;
  Eigen::Vector3d to_base_m(const Observation& obs) const;
  bool odometry_covers(int64_t utime) const;
  std::vector<ObservedStep> observed_with_overhang(const Observation& obs, const Pose4& pose) const;
  // x_uncertainty_m: how far off the position along the stair may be beyond what a registration on the
  // model's steps leaves (0: so registered; else the motion prior's drift since, or the end wall's own
  // uncertainty where it alone placed the camera); registration.position_uncertainty_m is added to it.
  // height_measured: this frame measured the pose's height (registered on the model's levels or
  // nosings, or perception's height over the surface beneath); else it was carried (height_measured_x_m_).
  void publish(const Observation& obs, const Pose4& pose, bool camera_valid, double x_uncertainty_m,
               bool height_measured);
  double prior_x_uncertainty_m(int64_t utime, bool with_odometry) const;
  bool prior_tells_steps_apart(int64_t utime, bool with_odometry) const;
  void note_speed_change();

  TrackerConfig config_;
  StairMap map_;
  DirectionFilter direction_;
  StairModel model_;
  OdometryPrior odometry_;
  // A recent accepted pose, for the velocity; to_base_m: camera centre -> the carrier's base origin in
  // the gravity-aligned camera frame at that pose (zero without a mount).
  struct Accepted {
    int64_t utime;
    Pose4 pose;
    Eigen::Vector3d to_base_m;
    // The point the motion prior keeps at constant velocity: the base with a mount, else the camera.
    Eigen::Vector3d base_m() const { return pose.point_at(to_base_m); }
  };
  std::deque<Accepted> accepted_;
  // A frame placed on the planes in view since the last accepted one: where the camera was last
  // seen, so the prior starts there (its velocity stays the accepted poses').
  std::optional<Accepted> placed_;
  // When the camera's position along the stair was last measured (registered on the model's risers,
  // nosings or end wall, not carried by the prior), how far off that measurement may be beyond the
  // registration's own uncertainty (m: the end wall's, where it alone placed the camera), and how much
  // its speed along the stair changed across the velocity window then (m/s): the prior's position may
  // be off by that speed times the time since.
  int64_t x_measured_utime_ = 0;
  double x_measured_uncertainty_m_ = 0.0;
  double speed_change_mps_ = 0.0;
  // A registration from the prior turned down since then for points that disagree with it: the prior
  // is off by more than ICP reaches, by how much unknown.
  bool prior_refuted_ = false;
  // Along the stair in W, the middle of the steps the last registered frame saw: the part of the model
  // (between links the prior placed) the camera's position is measured against.
  double registered_on_x_m_ = 0.0;
  // Along the stair in W, where the carrier's base (the camera without a mount) was when the height
  // was last measured: a height carried from there across a flight's end is unknown (stair_map.hpp).
  double height_measured_x_m_ = std::numeric_limits<double>::quiet_NaN();
  int64_t last_utime_ = 0;
  bool have_utime_ = false;
  int64_t dropped_out_of_order_ = 0, rejected_registrations_ = 0, resets_ = 0, time_jumps_ = 0;
};

}  // namespace stairs
