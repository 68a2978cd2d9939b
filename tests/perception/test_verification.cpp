// Verification (perception/verification.hpp): a solid flight passes, furniture
// that fits the grammar is refuted by the evidence a flight would leave.
#include "drivers/sim/furniture.hpp"
#include "drivers/sim/render.hpp"
#include "drivers/sim/trajectory.hpp"
#include "perception/pipeline.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>

namespace stairs {
namespace {

// Two steps of `first_m` and `second_m` rise (0.17 m each by default) and 0.28 m run, 1.0 m wide,
// their fronts 2.0 m ahead of a camera 1.4 m high pitched 35 deg down.
Observation two_steps(double first_m = 0.17, double second_m = 0.17) {
  sim::Scene s;
  s.kind = sim::SceneKind::FlatRoom;
  s.walls = sim::Walls::None;
  s.flat_length_m = 5.0;
  for (int k = 0; k < 2; ++k) {
    const double x0 = 2.0 + 0.28 * k, top = k == 0 ? first_m : first_m + second_m;
    s.boxes.push_back({{x0, -0.5, 0.0}, {x0 + 0.28 * (2 - k), 0.5, top}});
  }
  const Intrinsics K{640, 480, 525.0, 525.0, 319.5, 239.5};
  sim::Renderer r(s, K, sim::perfect_sensor(), 1);
  Pipeline p;
  return p.process(r.render(sim::camera_pose({0.0, 0.0, 1.4}, 0.0, -35.0, 0.0), 0, 0));
}

TEST(PerceptionVerification, ASolidFlightIsAStaircase) {
  const Observation o = two_steps();
  EXPECT_EQ(o.direction, Direction::Up) << o.status;
  EXPECT_GE(o.steps.size(), 2u) << o.status;
  EXPECT_EQ(o.status, "ok");
  for (const Step& st : o.steps) {
    if (!(st.inferred & kStepRiserInferred)) {
      EXPECT_NEAR(*st.riser_height_m, 0.17, 0.01);
    }
  }
}

// Two measured rises 9 cm apart are no flight, though each lies within rise_tolerance_m (5 cm) of
// their mean: a kitchen's chair back, table top and seat, seen from above, came out as rises of
// 17.6 and 27 cm. Two that differ by less than the tolerance are one.
TEST(PerceptionVerification, TwoMeasuredRisesThatDisagreeAreNoFlight) {
  const Observation odd = two_steps(0.15, 0.24);
  EXPECT_TRUE(odd.steps.empty()) << odd.status;
  EXPECT_NE(odd.status.find("rise irregular"), std::string::npos) << odd.status;
  const Observation regular = two_steps(0.17, 0.20);
  EXPECT_EQ(regular.steps.size(), 2u) << regular.status;
  for (const Step& st : regular.steps) EXPECT_FALSE(st.inferred & kStepRiserInferred);
}

// A kitchen table with chairs (stairs-sim's kitchen_table, size draws 2 and 6) seen from
// 1.4 m at 1.2 m: a chair seat and the table top fit the grammar as a
// two-step flight; beneath the seat's front the view runs on to the floor.
// Over three seconds of the walk, no frame is a staircase, and every frame the
// grammar alone (every check off) takes for a flight is refuted for that view.
TEST(PerceptionVerification, AChairBeforeATableIsNoStaircaseSeenThroughBeneathTheSeat) {
  PerceptionConfig unverified;
  VerificationConfig& v = unverified.verification;
  v.riser_support = v.foot_support = v.widths = v.alignment = v.regularity = false;
  int flights = 0;
  // Two size draws of the family: since planes are fitted away from depth jumps
  // (region_growing.fit_jump_ratio) the grammar takes 8 frames of draw 2 alone for a flight, fewer than
  // this test wants refuted; draw 6 adds 21. (Draws 1, 3, 4, 5: 0-10 such frames, none a staircase
  // either; two of them refuted by their rises, 0.77 m and 5 cm off the other, not beneath a seat.)
  for (const uint64_t draw : {2u, 6u}) {
    const sim::Scene scene = sim::furniture_scene("kitchen_table", draw);
    sim::TrajectoryConfig tc = sim::trajectory_defaults(sim::Carrier::HandHeld);
    tc.height_m = 1.4;
    tc.pitch_deg = -30;
    tc.fps = 10;
    const sim::Trajectory traj(scene, tc);
    sim::Renderer r(scene, Intrinsics{640, 480, 525.0, 525.0, 319.5, 239.5}, sim::SensorModel{}, 2);
    for (int k = 30; k < 60; ++k) {
      const DepthImage img = r.render(traj.pose(k), static_cast<int64_t>(traj.time_s(k) * 1e6), k);
      const Observation o = Pipeline().process(img);
      EXPECT_TRUE(o.steps.empty()) << "draw " << draw << " frame " << k << ": " << o.status;
      const Observation u = Pipeline(unverified).process(img);
      if (u.steps.size() < 2) continue;
      ++flights;
      EXPECT_NE(o.status.find("seen through beneath the nosing"), std::string::npos)
          << "draw " << draw << " frame " << k << ": " << o.status;
    }
  }
  std::printf("%d frames the grammar alone takes for a flight\n", flights);
  EXPECT_GE(flights, 10);
}

}  // namespace
}  // namespace stairs
