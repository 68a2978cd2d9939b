// Ground truth: pose scalars follow from the pose; visible steps; stair truth.
#include "drivers/sim/pose_truth.hpp"
#include "drivers/sim/render.hpp"
#include "drivers/sim/trajectory.hpp"

#include "common/cloud.hpp"

#include <gtest/gtest.h>

#include <algorithm>

using namespace stairs;
using namespace stairs::sim;

namespace {
Intrinsics kinect() { return {640, 480, 525.0, 525.0, 319.5, 239.5}; }
bool contains(const std::vector<int>& v, int k) { return std::find(v.begin(), v.end(), k) != v.end(); }
}  // namespace

TEST(SimTruth, PitchRollFollowFromThePose) {
  for (double yaw : {-170.0, -20.0, 0.0, 35.0, 180.0})
    for (double pitch : {-60.0, -45.0, -25.0, 0.0, 10.0})
      for (double roll : {-8.0, 0.0, 4.0}) {
        const Eigen::Isometry3d T = camera_pose({0.1, 0.2, 1.3}, yaw, pitch, roll);
        EXPECT_NEAR(pitch_deg(T), pitch, 1e-9);
        EXPECT_NEAR(roll_deg(T), roll, 1e-9);
        // Optical axis really points below the horizon by -pitch.
        EXPECT_NEAR(std::asin(T.linear().col(2).z()) * 180.0 / M_PI, pitch, 1e-9);
      }
  // Right side down: the image's +x axis points below the horizon.
  const Eigen::Isometry3d T = camera_pose({0, 0, 1}, 0.0, -30.0, 5.0);
  EXPECT_LT(T.linear().col(0).z(), 0.0);
}

TEST(SimTruth, HeightAndDistanceFollowFromThePose) {
  const Scene s = make_preset("straight_up");  // risers 0.18 at x = 0, 0.25, ...; top nosing at 2.25
  EXPECT_NEAR(height_m(s, camera_pose({-1.4, 0, 1.0}, 0, -35, 0)), 1.0, 1e-12);
  EXPECT_NEAR(height_m(s, camera_pose({0.3, 0, 1.5}, 0, -35, 0)), 1.5 - 0.36, 1e-12);
  EXPECT_NEAR(height_m(s, camera_pose({3.0, 0, 2.9}, 180, -35, 0)), 2.9 - 1.8, 1e-12);
  EXPECT_NEAR(*distance_m(s, camera_pose({-1.4, 0, 1.0}, 0, -35, 0)), 1.4, 1e-12);
  EXPECT_FALSE(distance_m(s, camera_pose({0.3, 0, 1.5}, 0, -35, 0)).has_value());
  EXPECT_NEAR(*distance_m(s, camera_pose({3.25, 0, 2.8}, 180, -35, 0)), 1.0, 1e-12);
  // Looking down from the floor: nothing ahead.
  EXPECT_FALSE(distance_m(s, camera_pose({-1.4, 0, 1.0}, 180, -35, 0)).has_value());

  const Scene two = make_preset("two_flights");  // mid landing x 1.5..2.7 at z 1.26
  EXPECT_NEAR(*distance_m(two, camera_pose({2.0, 0, 2.3}, 0, -35, 0)), 0.7, 1e-12);
  EXPECT_NEAR(*distance_m(two, camera_pose({2.0, 0, 2.3}, 180, -35, 0)), 0.5, 1e-12);
  EXPECT_NEAR(height_m(two, camera_pose({2.0, 0, 2.3}, 0, -35, 0)), 2.3 - 1.26, 1e-12);
}

TEST(SimTruth, FrameTruthMatchesTrajectoryPose) {
  const Scene s = make_preset("straight_up");
  Renderer r(s, kinect(), perfect_sensor(), 3);
  TrajectoryConfig c = trajectory_defaults(Carrier::HandHeld);
  const Trajectory traj(s, c);
  for (int f = 0; f < traj.frames(); f += 17) {
    const Eigen::Isometry3d T = traj.pose(f);
    const GroundTruthFrame g = r.truth(T, traj.time_s(f), r.render(T, 0, f));
    EXPECT_NEAR(g.pitch_deg, pitch_deg(T), 1e-12);
    EXPECT_GE(g.pitch_deg, -45.0);
    EXPECT_LE(g.pitch_deg, -25.0);
    EXPECT_NEAR(g.height_m, 1.0, 0.2);  // smoothed surface + 1 m, gait bounce
    EXPECT_TRUE(g.position_m.isApprox(T.translation()));
    EXPECT_TRUE(g.orientation.toRotationMatrix().isApprox(T.linear(), 1e-9));
  }
}

TEST(SimTruth, VisibleStepsCountValidPixels) {
  const Scene s = make_preset("straight_up");
  Renderer r(s, kinect(), perfect_sensor(), 3);
  EXPECT_EQ(r.visible_min_pixels(), 500);
  const Eigen::Isometry3d T = camera_pose({-1.5, 0, 1.0}, 0, -30, 0);
  const DepthImage img = r.render(T, 0, 0);
  const GroundTruthFrame g = r.truth(T, 0.0, img);
  EXPECT_TRUE(contains(g.visible_steps, 0));
  EXPECT_TRUE(contains(g.visible_steps, 1));
  EXPECT_FALSE(contains(g.visible_steps, 9));  // far beyond the view at -30 deg
  // The same pose with the depth wiped: nothing is visible.
  DepthImage empty = img;
  std::fill(empty.depth.begin(), empty.depth.end(), 0);
  EXPECT_TRUE(r.truth(T, 0.0, empty).visible_steps.empty());
  // Turned away from the stair.
  const Eigen::Isometry3d away = camera_pose({-1.5, 0, 1.0}, 180, -30, 0);
  EXPECT_TRUE(r.truth(away, 0.0, r.render(away, 0, 1)).visible_steps.empty());

  Renderer small(s, scale_intrinsics(kinect(), 320, 240), perfect_sensor(), 3);
  EXPECT_EQ(small.visible_min_pixels(), 125);
}

TEST(SimTruth, StairTruthFollowsDesign) {
  Scene s = make_preset("two_flights");
  s.nosing_m = 0.02;
  const GroundTruth gt = scene_truth(s);
  ASSERT_EQ(gt.flights.size(), 2u);
  ASSERT_EQ(gt.flights[0].steps.size(), 7u);
  const Step& first = gt.flights[0].steps[0];
  EXPECT_NEAR(*first.riser_height_m, 0.18, 1e-12);
  EXPECT_NEAR(*first.tread_depth_m, 0.25, 1e-12);
  EXPECT_NEAR(first.nosing_m.x(), -0.02, 1e-12);
  EXPECT_NEAR(first.nosing_m.z(), 0.18, 1e-12);
  const Step& mid = gt.flights[0].steps.back();
  EXPECT_TRUE(mid.landing);
  EXPECT_NEAR(*mid.tread_depth_m, 1.2, 1e-12);
  EXPECT_NEAR(mid.nosing_m.z(), 7 * 0.18, 1e-12);
  const Step& second = gt.flights[1].steps[0];
  EXPECT_NEAR(second.nosing_m.x(), 1.5 + 1.2 - 0.02, 1e-12);
  EXPECT_NEAR(second.nosing_m.z(), 8 * 0.18, 1e-12);
  EXPECT_TRUE(gt.flights[1].steps.back().landing);
  EXPECT_NEAR(*gt.flights[1].steps.back().tread_depth_m, 3.0, 1e-12);
  EXPECT_TRUE(scene_truth(make_preset("flat_room")).flights.empty());
  EXPECT_TRUE(scene_truth(make_preset("ramp")).flights.empty());
}

TEST(SimTruth, ScenarioJsonRoundTripsAndNamesBadKeys) {
  for (const std::string& name : preset_names()) {
    const Scene s = make_preset(name);
    const Scene back = scene_from_json(scene_to_json(s), "test");
    EXPECT_EQ(scene_to_json(back), scene_to_json(s)) << name;
  }
  try {
    scene_from_json(nlohmann::json{{"flights", {{{"steps", 5}, {"riser_m", -0.1}}}}}, "my.json");
    FAIL() << "negative riser accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("my.json"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("riser_m"), std::string::npos);
  }
  EXPECT_THROW(make_preset("spiral"), std::invalid_argument);
}

// A round trip: up the whole flight, a half turn on the spot on the top landing
// (the height stays that of the landing, the heading turns through 180 deg),
// and back down to where it started, facing the other way.
TEST(SimTruth, RoundTripTurnsOnTheTopLandingAndComesBack) {
  const Scene s = make_preset("straight_up");
  TrajectoryConfig c = trajectory_defaults(Carrier::Robot);
  c.situation = Situation::RoundTrip;
  c.wobble = 0;
  const Trajectory traj(s, c);
  const Eigen::Isometry3d first = traj.pose(0), last = traj.pose(traj.frames() - 1);
  const double top_z = step_geometry(s).back().top_z_m;
  const double leg_s = (traj.end_x_m() - traj.start_x_m()) / c.speed_mps;
  EXPECT_NEAR(traj.frames() / c.fps, 2 * leg_s + c.turn_s, 0.2);
  EXPECT_NEAR(last.translation().x(), first.translation().x(), 0.05);
  EXPECT_NEAR(last.translation().z(), first.translation().z(), 1e-6);
  // Optical axes: forward up the stair at the start, down it at the end.
  EXPECT_GT(first.linear().col(2).x(), 0.9);
  EXPECT_LT(last.linear().col(2).x(), -0.9);
  for (double f : {0.1, 0.5, 0.9}) {
    const Eigen::Isometry3d T = traj.pose_at(leg_s + f * c.turn_s);
    EXPECT_NEAR(T.translation().x(), traj.end_x_m(), 1e-9);
    EXPECT_NEAR(T.translation().z(), top_z + c.height_m, 1e-6);
  }
}

// Issue 15, outputs in the robot's base frame: the robot carrier is a rigid body. Its base (the
// camera carried back through the mount) stands on the floor level before the stair and between
// the levels of the stair under it on the flight, its z axis tilted by the body's pitch alone.
TEST(SimTruth, ARobotCarriesItsCameraOnARigidMount) {
  const Scene s = make_preset("straight_up");
  TrajectoryConfig c = trajectory_defaults(Carrier::Robot);
  c.wobble = 0;
  const Trajectory traj(s, c);
  const MountConfig mount = c.mount();
  ASSERT_TRUE(mount.configured());
  const double rise = step_geometry(s).front().top_z_m;
  const std::vector<StepGeometry> steps = step_geometry(s);
  std::vector<double> flight_tilt_deg;  // with the whole track (+-0.35 m) on the flight
  for (int f = 0; f < traj.frames(); ++f) {
    const Eigen::Isometry3d base = traj.pose(f) * camera_in_base(mount).inverse();
    const Eigen::Vector3d p = base.translation(), z = base.linear().col(2), y = base.linear().col(1);
    EXPECT_NEAR(y.z(), 0.0, 1e-9) << "frame " << f << ": no roll without wobble";
    const double surface = surface_height_m(s, p.x(), p.y());
    EXPECT_GE(p.z(), surface - rise - 1e-9) << "frame " << f;
    EXPECT_LE(p.z(), surface + rise + 1e-9) << "frame " << f;
    if (p.x() > steps.front().riser_x_m + 0.35 && p.x() < steps.back().riser_x_m - 0.35)
      flight_tilt_deg.push_back(std::acos(z.z()) * 180.0 / M_PI);
  }
  // On the floor before the stair: level, on the floor, the camera straight above at the mount's height.
  const Eigen::Isometry3d cam0 = traj.pose(0), base0 = cam0 * camera_in_base(mount).inverse();
  EXPECT_NEAR(base0.translation().z(), 0.0, 1e-9);
  EXPECT_NEAR(base0.linear().col(2).z(), 1.0, 1e-9);
  EXPECT_NEAR(cam0.translation().z(), c.height_m, 1e-6);  // the mount holds floats
  // On the flight the body tilts with the stair's slope (atan(0.18 / 0.25) = 35.8 deg).
  ASSERT_GT(flight_tilt_deg.size(), 10u);
  std::nth_element(flight_tilt_deg.begin(), flight_tilt_deg.begin() + flight_tilt_deg.size() / 2, flight_tilt_deg.end());
  EXPECT_NEAR(flight_tilt_deg[flight_tilt_deg.size() / 2], std::atan(0.18 / 0.25) * 180.0 / M_PI, 0.5);
}


// A hand-held camera's roll (--roll) is the hand's, under the gait's +-2 deg: the truth's roll
// averages to it over a walk and stays within the wobble of it.
TEST(SimTruth, AHandHeldRollIsHeldUnderTheWobble) {
  const Scene s = make_preset("straight_up");
  TrajectoryConfig c = trajectory_defaults(Carrier::HandHeld);
  c.roll_deg = 7.0;
  const Trajectory traj(s, c);
  double sum = 0.0;
  for (int f = 0; f < traj.frames(); ++f) {
    const double roll = roll_deg(traj.pose(f));
    EXPECT_NEAR(roll, 7.0, 2.5) << f;
    sum += roll;
  }
  EXPECT_NEAR(sum / traj.frames(), 7.0, 0.5);
}
