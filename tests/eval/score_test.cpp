#include "tools/score.hpp"

#include "fixtures.hpp"

#include <gtest/gtest.h>

namespace stairs::eval {
namespace {

using namespace test;

struct FabricatedRun {
  GroundTruth truth = straight_stair();
  std::vector<FrameResult> frames;
  std::vector<Flight> model = truth.flights;

  FabricatedRun() {
    const double xs[] = {-2.0, -1.6, -1.2};
    for (double x : xs) {
      FrameResult f;
      f.truth = camera_frame(x, 0.1, 1.0, -35.0);
      f.camera.valid = true;
      f.camera.pitch_deg = -35.0;
      f.camera.height_m = 1.0;
      f.steps = perfect_detections(truth, *f.truth);
      f.latency = {{"perception", 5.0}, {"tracker", 1.0}};
      frames.push_back(f);
    }
  }
  Score score() const { return score_run(frames, &model, truth); }
};

TEST(EvalScore, PerfectResultScoresFullAndZeroError) {
  const Score s = FabricatedRun().score();
  EXPECT_EQ(s.frames_scored, 3);
  EXPECT_EQ(s.visible_steps, 3 * kSteps);
  ASSERT_TRUE(s.frame_step_detection);
  EXPECT_DOUBLE_EQ(*s.frame_step_detection, 1.0);
  EXPECT_EQ(s.frame_false_steps, 0);
  EXPECT_TRUE(s.model_scored);
  EXPECT_EQ(s.model_steps_detected, kSteps);
  EXPECT_EQ(s.model_steps_real, kSteps);
  EXPECT_EQ(s.model_false_steps, 0);
  EXPECT_EQ(s.model_step_offset, 0);
  EXPECT_EQ(s.riser_error_cm.n, kSteps);         // the landing's riser counts
  EXPECT_EQ(s.tread_error_cm.n, kSteps - 1);     // its depth does not
  EXPECT_NEAR(*s.riser_error_cm.mean_signed, 0.0, 1e-9);
  EXPECT_NEAR(*s.riser_error_cm.mean_abs, 0.0, 1e-9);
  EXPECT_NEAR(*s.tread_error_cm.mean_abs, 0.0, 1e-9);
  EXPECT_EQ(s.pose_frames_valid, 3);
  EXPECT_NEAR(*s.pitch_error_deg.mean_abs, 0.0, 1e-9);
  EXPECT_NEAR(*s.roll_error_deg.mean_abs, 0.0, 1e-9);
  EXPECT_NEAR(*s.height_error_cm.mean_abs, 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(s.latency_ms.at("perception").median_ms, 5.0);
}

TEST(EvalScore, DroppedStepShowsUpExactly) {
  FabricatedRun run;
  for (auto& f : run.frames) f.steps.erase(f.steps.begin() + 2);
  run.model[0].steps.erase(run.model[0].steps.begin() + 2);
  const Score s = run.score();
  EXPECT_DOUBLE_EQ(*s.frame_step_detection, 12.0 / 15.0);
  EXPECT_EQ(s.frame_false_steps, 0);
  EXPECT_EQ(s.model_steps_detected, kSteps - 1);
  EXPECT_EQ(s.model_steps_real, kSteps);
  EXPECT_EQ(s.model_false_steps, 0);
}

TEST(EvalScore, RiserBiasShowsUpExactly) {
  FabricatedRun run;
  for (Step& st : run.model[0].steps) st.riser_height_m = *st.riser_height_m + 0.02;
  run.model[0].steps.back().tread_depth_m = 0.5;  // a half-seen landing is no tread error
  const Score s = run.score();
  EXPECT_NEAR(*s.riser_error_cm.mean_signed, 2.0, 1e-9);
  EXPECT_NEAR(*s.riser_error_cm.mean_abs, 2.0, 1e-9);
  EXPECT_NEAR(*s.tread_error_cm.mean_signed, 0.0, 1e-9);
  EXPECT_NEAR(*s.tread_error_cm.mean_abs, 0.0, 1e-9);
}

TEST(EvalScore, MeanAbsoluteAndSignedDiffer) {
  FabricatedRun run;
  run.model[0].steps[0].tread_depth_m = kTread + 0.01;
  run.model[0].steps[1].tread_depth_m = kTread - 0.03;
  const Score s = run.score();
  EXPECT_NEAR(*s.tread_error_cm.mean_signed, -2.0 / 4, 1e-9);
  EXPECT_NEAR(*s.tread_error_cm.mean_abs, 4.0 / 4, 1e-9);
}

TEST(EvalScore, FalseStepsCountedPerFrameAndInModel) {
  FabricatedRun run;
  Step bogus;
  bogus.nosing_m = {6.0, 0.0, 0.5};
  run.frames[1].steps.push_back(bogus);
  run.model[0].steps.push_back(bogus);  // 6 m along x: no real step there
  const Score s = run.score();
  EXPECT_EQ(s.frame_false_steps, 1);
  EXPECT_EQ(s.frames_with_false_steps, 1);
  EXPECT_DOUBLE_EQ(*s.frame_step_detection, 1.0);
  EXPECT_EQ(s.model_false_steps, 1);
  EXPECT_EQ(s.model_steps_detected, kSteps);
}

TEST(EvalScore, TrackedStepsScoredApartFromPerception) {
  FabricatedRun run;
  EXPECT_FALSE(run.score().frame_step_detection_tracked) << "no tracker ran: no tracked score";
  // Perception misses step 2 everywhere; the tracker knows every step on the
  // first two frames, has no camera on the third, and adds one bogus step.
  for (size_t i = 0; i < run.frames.size(); ++i) {
    FrameResult& f = run.frames[i];
    f.tracked_steps = i < 2 ? f.steps : std::vector<Step>{};
    f.steps.erase(f.steps.begin() + 2);
  }
  Step bogus;
  bogus.nosing_m = {6.0, 0.0, 0.5};
  run.frames[0].tracked_steps->push_back(bogus);
  const Score s = run.score();
  EXPECT_DOUBLE_EQ(*s.frame_step_detection, 12.0 / 15.0);
  ASSERT_TRUE(s.frame_step_detection_tracked);
  EXPECT_EQ(s.tracked_steps_matched, 10);
  EXPECT_DOUBLE_EQ(*s.frame_step_detection_tracked, 10.0 / 15.0);
  EXPECT_EQ(s.tracked_false_steps, 1);
  EXPECT_EQ(s.frame_false_steps, 0);
}

// The tracker's camera: its step beneath is put on the real steps through the
// frame's tracked-step matches; coverage counts from its first valid frame.
TEST(EvalScore, TrackedCameraAgainstTheTruth) {
  FabricatedRun run;
  for (FrameResult& f : run.frames) {
    f.tracked_steps = f.steps;  // the model's steps in the model's order
    TrackedCamera c;
    c.valid = true;
    c.height_m = 1.0;
    c.step_index = -1;
    c.position_m = f.truth->position_m + Eigen::Vector3d(0.01, 0.0, 0.0);
    f.tracked_camera = c;
  }
  run.frames[1].tracked_camera->step_index = 0;  // the wrong step, a rise too low
  run.frames[1].tracked_camera->height_m = 1.0 - 0.18;
  run.frames[2].tracked_camera->valid = false;
  run.frames[2].tracked_steps = std::vector<Step>{};
  const Score s = run.score();
  EXPECT_EQ(s.tracked_camera_frames, 2);
  EXPECT_EQ(s.tracked_beneath_frames, 2);
  ASSERT_TRUE(s.tracked_camera_coverage && s.tracked_step_index_accuracy);
  EXPECT_DOUBLE_EQ(*s.tracked_camera_coverage, 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(*s.tracked_step_index_accuracy, 0.5);
  EXPECT_NEAR(*s.tracked_height_error_cm.mean_abs, 9.0, 1e-9);
  EXPECT_NEAR(*s.tracked_position_error_cm.mean_abs, 1.0, 1e-9);
  ASSERT_TRUE(s.frames[1] && s.frames[1]->tracked_step_index);
  EXPECT_EQ(*s.frames[1]->tracked_step_index, 0);
  EXPECT_EQ(s.frames[1]->true_step_index, -1);
  EXPECT_FALSE(s.frames[2]->tracked_step_index);
  // A model one step short at the bottom: its step 0 is real step 1.
  for (FrameResult& f : run.frames)
    if (!f.tracked_steps->empty()) f.tracked_steps->erase(f.tracked_steps->begin());
  EXPECT_EQ(*run.score().frames[1]->tracked_step_index, 1);
}

TEST(EvalScore, MatchToleranceIsHalfTreadAndHalfRiser) {
  FabricatedRun run;
  auto& steps = run.frames[0].steps;
  steps[0].nosing_m.x() += 0.5 * kTread - 1e-6;  // inside
  steps[1].nosing_m.z() += 0.5 * kRiser + 1e-3;  // outside
  const Score s = run.score();
  EXPECT_EQ(s.frame_steps_matched, 3 * kSteps - 1);
  EXPECT_EQ(s.frame_false_steps, 1);
}

TEST(EvalScore, EachRealStepMatchesAtMostOnce) {
  FabricatedRun run;
  run.frames[0].steps.push_back(run.frames[0].steps[0]);  // a duplicate detection
  const Score s = run.score();
  EXPECT_EQ(s.frame_steps_matched, 3 * kSteps);
  EXPECT_EQ(s.frame_false_steps, 1);
}

TEST(EvalScore, ModelAlignedByWholeStepOffset) {
  FabricatedRun run;
  // The tracker put its origin on real step 1 and never saw step 0.
  auto& steps = run.model[0].steps;
  steps.erase(steps.begin());
  for (Step& st : steps) st.nosing_m -= Eigen::Vector3d(kTread, 0.0, kRiser);
  const Score s = run.score();
  EXPECT_EQ(s.model_step_offset, 1);
  EXPECT_EQ(s.model_steps_detected, kSteps - 1);
  EXPECT_EQ(s.model_false_steps, 0);
  EXPECT_NEAR(*s.riser_error_cm.mean_abs, 0.0, 1e-9);
}

TEST(EvalScore, LandingDecidesAmongEquallyGoodOffsets) {
  FabricatedRun run;
  // The tracker saw the top three steps, landing included, with its origin on
  // real step 2: on this uniform flight offsets 0, 1 and 2 all match three.
  auto& steps = run.model[0].steps;
  steps.erase(steps.begin(), steps.begin() + 2);
  for (Step& st : steps) st.nosing_m -= Eigen::Vector3d(2 * kTread, 0.0, 2 * kRiser);
  const Score s = run.score();
  EXPECT_EQ(s.model_step_offset, 2);
  EXPECT_EQ(s.model_steps_detected, 3);
  EXPECT_EQ(s.tread_error_cm.n, 2);
  EXPECT_NEAR(*s.tread_error_cm.mean_abs, 0.0, 1e-9);
}

TEST(EvalScore, PoseErrorsOverValidFramesOnly) {
  FabricatedRun run;
  run.frames[0].camera.pitch_deg = -34.0;
  run.frames[0].camera.roll_deg = -0.5;
  run.frames[0].camera.height_m = 1.03;
  run.frames[1].camera.height_m.reset();  // unknown height: not scored
  run.frames[2].camera.valid = false;
  run.frames[2].camera.pitch_deg = 80.0;  // ignored: not valid
  const Score s = run.score();
  EXPECT_EQ(s.pose_frames_valid, 2);
  EXPECT_NEAR(*s.pitch_error_deg.mean_abs, 0.5, 1e-9);
  EXPECT_NEAR(*s.roll_error_deg.mean_abs, 0.25, 1e-9);
  EXPECT_EQ(s.height_error_cm.n, 1);
  EXPECT_NEAR(*s.height_error_cm.mean_abs, 3.0, 1e-9);
}

TEST(EvalScore, BeneathInViewFromTheTrueGeometry) {
  // Kinect v1: the bottom row is 24.57 deg below the optical axis; at pitch
  // -35 deg it meets a surface 1 m below at 0.587 m (visible with 5 cm more).
  const Intrinsics K{640, 480, 525.0, 525.0, 319.5, 239.5};
  const std::vector<Step> real = real_steps(straight_stair());
  EXPECT_TRUE(beneath_in_view(camera_frame(-2.0, 0.0, 1.0, -35.0), real, K));
  EXPECT_TRUE(beneath_in_view(camera_frame(-0.7, 0.0, 1.0, -35.0), real, K));
  EXPECT_FALSE(beneath_in_view(camera_frame(-0.5, 0.0, 1.0, -35.0), real, K));  // floor ends at the riser
  EXPECT_FALSE(beneath_in_view(camera_frame(0.1, 0.0, 1.18, -35.0), real, K));  // on the first tread
  // Going down from the top landing (nosing at x = 1.12, z = 0.9).
  EXPECT_TRUE(beneath_in_view(camera_frame(1.92, 0.0, 1.9, -35.0, 180.0), real, K));
  EXPECT_FALSE(beneath_in_view(camera_frame(1.5, 0.0, 1.9, -35.0, 180.0), real, K));
  // Looking straight down the point beneath is always in view.
  EXPECT_TRUE(beneath_in_view(camera_frame(0.1, 0.0, 1.18, -89.0), real, K));
}

TEST(EvalScore, HeightErrorWhereTheSurfaceBeneathIsInView) {
  FabricatedRun run;
  for (FrameResult& f : run.frames) f.K = Intrinsics{640, 480, 525.0, 525.0, 319.5, 239.5};
  run.frames[2].truth = camera_frame(-0.5, 0.1, 1.0, -35.0);  // floor beneath out of view
  run.frames[2].camera.height_m = 1.18;
  run.frames[0].camera.height_m = 1.02;
  const Score s = run.score();
  EXPECT_EQ(s.height_error_cm.n, 3);
  EXPECT_NEAR(*s.height_error_cm.mean_abs, 20.0 / 3, 1e-9);
  EXPECT_EQ(s.height_error_beneath_visible_cm.n, 2);
  EXPECT_NEAR(*s.height_error_beneath_visible_cm.mean_abs, 1.0, 1e-9);
}

TEST(EvalScore, NosingInViewByProjection) {
  const Intrinsics K{640, 480, 525.0, 525.0, 319.5, 239.5};
  const std::vector<Step> real = real_steps(straight_stair());
  const GroundTruthFrame approach = camera_frame(-2.0, 0.0, 1.0, -35.0);
  EXPECT_TRUE(nosing_in_view(approach, real[0], K));    // 12.7 deg above the optical axis
  EXPECT_FALSE(nosing_in_view(approach, real[4], K));   // 33.2 deg above it: beyond the top row
  // At the top going down, the landing's own edge is 34 deg below the axis.
  EXPECT_FALSE(nosing_in_view(camera_frame(1.5, 0.0, 1.9, -35.0, 180.0), real[4], K));
  EXPECT_TRUE(nosing_in_view(camera_frame(1.5, 0.0, 1.9, -35.0, 180.0), real[2], K));
  // Behind the camera.
  EXPECT_FALSE(nosing_in_view(camera_frame(0.5, 0.0, 1.2, -35.0), real[0], K));
}

TEST(EvalScore, NoModelLeavesModelScoresUnset) {
  FabricatedRun run;
  const Score s = score_run(run.frames, nullptr, run.truth);
  EXPECT_FALSE(s.model_scored);
  EXPECT_FALSE(s.riser_error_cm.mean_abs);
}

TEST(EvalScore, GravityFrameFollowsTrueCameraPose) {
  const GroundTruth gt = straight_stair();
  const GroundTruthFrame fr = camera_frame(-1.5, 0.3, 1.1, -40.0, 20.0);
  const Step& s = gt.flights[0].steps[3];
  // At lateral coordinate 0 a line crossing a heading yawed by psi lies
  // (nx - x) / cos(psi) ahead (worked out by hand).
  const Eigen::Vector3d n = true_nosing_in_gravity_frame(s, fr, 0.0);
  EXPECT_NEAR(n.x(), (s.nosing_m.x() + 1.5) / std::cos(20.0 * M_PI / 180.0), 1e-9);
  EXPECT_NEAR(n.y(), 0.0, 1e-9);
  EXPECT_NEAR(n.z(), s.nosing_m.z() - 1.1, 1e-9);
}

TEST(EvalScore, DescendingCameraMatchesToo) {
  GroundTruth gt = straight_stair();
  // Camera above the landing looking down the flight (-x).
  const GroundTruthFrame fr = camera_frame(1.8, 0.0, 0.9 + 1.7, -40.0, 180.0);
  std::vector<Step> det;
  for (const Step& s : gt.flights[0].steps) {
    Step d = s;
    d.nosing_m = {fr.position_m.x() - s.nosing_m.x(), 0.0, s.nosing_m.z() - fr.position_m.z()};
    det.push_back(d);
  }
  const auto m = match_frame_steps(det, real_steps(gt), fr);
  ASSERT_EQ(m.size(), size_t(kSteps));
  for (const StepMatch& x : m) EXPECT_EQ(x.detected, x.real);
}

TEST(EvalScore, LatencyMedianAndNearestRankP95) {
  std::vector<double> v;
  for (int i = 20; i >= 1; --i) v.push_back(i);
  const LatencyStats s = latency_stats(v);
  EXPECT_EQ(s.n, 20);
  EXPECT_DOUBLE_EQ(s.median_ms, 10.5);
  EXPECT_DOUBLE_EQ(s.p95_ms, 19.0);
  EXPECT_DOUBLE_EQ(latency_stats({3.0, 1.0, 2.0}).median_ms, 2.0);
}

}  // namespace
}  // namespace stairs::eval
