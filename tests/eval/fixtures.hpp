// A fabricated straight stair and camera, computed by hand (not by the code
// under test), for the scoring and Result JSON tests.
#pragma once

#include "common/types.hpp"

#include <cmath>

namespace stairs::eval::test {

constexpr double kRiser = 0.18, kTread = 0.28, kLanding = 1.2;
constexpr int kSteps = 5;  // the last one is the top landing

inline GroundTruth straight_stair() {
  GroundTruth gt;
  gt.scene = "fabricated";
  Flight f;
  f.width_m = 1.0;
  for (int k = 0; k < kSteps; ++k) {
    Step s;
    s.riser_height_m = kRiser;
    s.landing = k == kSteps - 1;
    s.tread_depth_m = s.landing ? kLanding : kTread;
    s.width_m = 1.0;
    s.nosing_m = {k * kTread, 0.0, (k + 1) * kRiser};
    f.steps.push_back(s);
  }
  gt.flights.push_back(f);
  return gt;
}

// Camera at (x, y, z) in the stair frame, heading yaw about z (0 = along +x),
// optical axis pitch_deg above the horizon.
inline GroundTruthFrame camera_frame(double x, double y, double z, double pitch_deg, double yaw_deg = 0.0) {
  const double p = pitch_deg * M_PI / 180.0, w = yaw_deg * M_PI / 180.0;
  const Eigen::Vector3d forward(std::cos(p) * std::cos(w), std::cos(p) * std::sin(w), std::sin(p));
  const Eigen::Vector3d right(std::sin(w), -std::cos(w), 0.0);
  const Eigen::Vector3d down = forward.cross(right);
  Eigen::Matrix3d R;
  R.col(0) = right;
  R.col(1) = down;
  R.col(2) = forward;
  GroundTruthFrame fr;
  fr.pitch_deg = pitch_deg;
  fr.height_m = z;
  fr.position_m = {x, y, z};
  fr.orientation = Eigen::Quaterniond(R);
  for (int k = 0; k < kSteps; ++k) fr.visible_steps.push_back(k);
  return fr;
}

// Perfect detections of every step for a camera with zero yaw: nosing at
// [forward, left, up] = [nx - x, 0, nz - z], nearest first.
inline std::vector<Step> perfect_detections(const GroundTruth& gt, const GroundTruthFrame& fr) {
  std::vector<Step> out;
  for (const Step& s : gt.flights[0].steps) {
    Step d = s;
    d.nosing_m = {s.nosing_m.x() - fr.position_m.x(), 0.0, s.nosing_m.z() - fr.position_m.z()};
    out.push_back(d);
  }
  return out;
}

}  // namespace stairs::eval::test
