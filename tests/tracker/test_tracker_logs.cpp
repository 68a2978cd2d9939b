// Accuracy of the fused model on simulated sequences with the Kinect sensor
// model on: stairs-sim renders, perception observes, the tracker fuses, all
// in-process through the libraries. The final model must hold every real step,
// with mean absolute riser and tread errors <= 1 cm (landing depths excluded)
// and no false steps (DESIGN.md scores: model_steps_*, riser/tread_error_cm, false_steps).
#include "drivers/sim/render.hpp"
#include "drivers/sim/scene.hpp"
#include "drivers/sim/trajectory.hpp"
#include "perception/pipeline.hpp"
#include "tracker/tracker.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace stairs;

namespace {

struct Sequence {
  const char* preset;
  bool descending;
  double speed_mps;
  int keep_every = 1;               // 2 = every other frame dropped (15 fps)
  double gap_from_s = -1, gap_to_s = -1;  // frames missing in between
};

struct ModelScore {
  int real = 0, matched = 0, false_steps = 0;
  double riser_abs_cm = 0, tread_abs_cm = 0;
};

// The scorer's alignment: the whole-step offset that matches most steps.
ModelScore score(const StairModel& model, const GroundTruth& truth) {
  std::vector<Step> real, steps;
  for (const auto& f : truth.flights) real.insert(real.end(), f.steps.begin(), f.steps.end());
  for (const auto& f : model.flights) steps.insert(steps.end(), f.steps.begin(), f.steps.end());
  ModelScore best;
  best.matched = -1;
  for (size_t off = 0; off < real.size(); ++off) {
    const double ox = real[off].nosing_m.x(), oz = real[off].nosing_m.z() - *real[off].riser_height_m;
    ModelScore s;
    s.real = static_cast<int>(real.size());
    std::vector<bool> used(real.size(), false);
    int nr = 0, nt = 0;
    for (const Step& m : steps) {
      int hit = -1;
      for (size_t i = 0; i < real.size() && hit < 0; ++i) {
        const double half_tread = 0.5 * std::min(real[i].tread_depth_m.value_or(0.3), 0.3);
        if (!used[i] && std::abs(m.nosing_m.x() - (real[i].nosing_m.x() - ox)) < half_tread &&
            std::abs(m.nosing_m.z() - (real[i].nosing_m.z() - oz)) < 0.5 * *real[i].riser_height_m)
          hit = static_cast<int>(i);
      }
      if (hit < 0) {
        ++s.false_steps;
        continue;
      }
      used[hit] = true;
      ++s.matched;
      if (m.riser_height_m) s.riser_abs_cm += 100 * std::abs(*m.riser_height_m - *real[hit].riser_height_m), ++nr;
      if (m.tread_depth_m && !real[hit].landing && !m.landing)
        s.tread_abs_cm += 100 * std::abs(*m.tread_depth_m - *real[hit].tread_depth_m), ++nt;
    }
    if (nr) s.riser_abs_cm /= nr;
    if (nt) s.tread_abs_cm /= nt;
    if (s.matched > best.matched) best = s;
  }
  return best;
}

void run(const Sequence& seq) {
  const sim::Scene scene = sim::make_preset(seq.preset);
  sim::TrajectoryConfig tc = sim::trajectory_defaults(sim::Carrier::HandHeld);
  tc.descending = seq.descending;
  tc.speed_mps = seq.speed_mps;
  const sim::Trajectory trajectory(scene, tc);
  const Intrinsics K{640, 480, 525, 525, 319.5, 239.5};
  sim::Renderer renderer(scene, K, sim::SensorModel{}, 7);
  Pipeline perception;
  Tracker tracker;
  int frames = 0;
  for (int k = 0; k < trajectory.frames(); k += seq.keep_every) {
    const double t = trajectory.time_s(k);
    if (t >= seq.gap_from_s && t < seq.gap_to_s) continue;
    const DepthImage img = renderer.render(trajectory.pose(k), static_cast<int64_t>(t * 1e6), k);
    tracker.update(perception.process(img));
    ++frames;
  }
  const StairModel& m = tracker.model();
  const ModelScore s = score(m, renderer.stair_truth());
  std::printf("[%s %s %.1f m/s keep 1/%d gap %.1f-%.1f s] frames %d fused %d rejected %lld: steps %d/%d, "
              "false %d, riser %.2f cm, tread %.2f cm\n",
              seq.preset, seq.descending ? "down" : "up", seq.speed_mps, seq.keep_every, seq.gap_from_s,
              seq.gap_to_s, frames, m.observations_fused, static_cast<long long>(tracker.rejected_registrations()),
              s.matched, s.real, s.false_steps, s.riser_abs_cm, s.tread_abs_cm);
  EXPECT_EQ(s.matched, s.real);
  EXPECT_EQ(s.false_steps, 0);
  EXPECT_LE(s.riser_abs_cm, 1.0);
  EXPECT_LE(s.tread_abs_cm, 1.0);
}

}  // namespace

TEST(TrackerLogs, StraightUpSlow) { run({"straight_up", false, 0.3}); }
TEST(TrackerLogs, StraightUpWalking) { run({"straight_up", false, 0.6}); }
TEST(TrackerLogs, StraightUpWalking15fps) { run({"straight_up", false, 0.6, 2}); }
TEST(TrackerLogs, StraightUpWalkingOneSecondGap) { run({"straight_up", false, 0.6, 1, 2.0, 3.0}); }
TEST(TrackerLogs, StraightDownSlow) { run({"straight_down", true, 0.3}); }
TEST(TrackerLogs, StraightDownWalking) { run({"straight_down", true, 0.6}); }
TEST(TrackerLogs, TwoFlightsUpWalking) { run({"two_flights", false, 0.6}); }
TEST(TrackerLogs, TwoFlightsDownWalking) { run({"two_flights", true, 0.6}); }
