// The motion prior from odometry (issue 15): where a robot has wheel, leg or
// visual-inertial odometry, the camera's motion between two frames comes from
// it instead of a constant-velocity guess, so a gap of seconds, a stop or a
// turn on a landing keeps the camera on the model. Odometry drifts but never
// jumps: only its motion over the interval is used, turned into the stair
// frame about gravity.
#pragma once

#include "common/types.hpp"
#include "tracker/pose.hpp"

#include <deque>
#include <optional>

namespace stairs {

class OdometryPrior {
 public:
  // max_age_s: a time this long after the last sample holds it, later is not
  // covered; max_samples: history cap, the oldest go first; jump_back_s: a
  // sample this much older than the last starts a new stream (TrackerConfig).
  OdometryPrior(double max_age_s, size_t max_samples, double jump_back_s)
      : max_age_s_(max_age_s), max_samples_(max_samples), jump_back_s_(jump_back_s) {}

  // Samples in time order; an older or equal one is dropped and counted,
  // unless it is older by more than jump_back_s: then the history restarts.
  void add(const OdometrySample& o);
  // Forgets samples before utime, keeping the one bracketing it.
  void forget_before(int64_t utime);
  void clear() { samples_.clear(); }

  // The pose `from` moved by the odometry's motion from from_utime to
  // to_utime (translation turned about gravity by the heading difference at
  // from_utime; yaw by the heading change). None where odometry does not
  // cover both times.
  std::optional<Pose4> predict(const Pose4& from, int64_t from_utime, int64_t to_utime) const;
  bool covers(int64_t from_utime, int64_t to_utime) const { return at(from_utime) && at(to_utime); }

  int64_t dropped() const { return dropped_; }

 private:
  std::optional<OdometrySample> at(int64_t utime) const;  // interpolated, or the last one held

  double max_age_s_;
  size_t max_samples_;
  double jump_back_s_;
  std::deque<OdometrySample> samples_;
  int64_t dropped_ = 0;
};

// Heading (rad, about z from +x) of a camera optical frame's horizontal
// viewing direction; looking straight down, that of the image's up.
double optical_heading_rad(const Eigen::Quaterniond& optical_to_world);

}  // namespace stairs
