// The tracker on hand-built observations of known staircases (see
// drivers/sim/synthetic_observations.hpp): the model must hold every real step, with riser and
// tread errors under 1 cm and no false steps, at slow and walking speed, with
// dropped frames and gaps, ascending, descending and over two flights.
#include "drivers/sim/synthetic_observations.hpp"
#include "tracker/config.hpp"
#include "tracker/merge.hpp"
#include "tracker/model_output.hpp"
#include "tracker/prior_links.hpp"
#include "tracker/registration.hpp"
#include "tracker/relocalisation.hpp"
#include "tracker/tracker.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>

using namespace stairs;
using namespace stairs::synthetic;

namespace {

struct Walk {
  StairModel model;
  int64_t rejected = 0;
  int frames = 0;
};

// Every `keep`-th frame; frames in [gap_from, gap_to) are missing.
Walk walk_stair(const StairGeometry& g, bool ascending, double speed, int keep = 1, int gap_from = -1, int gap_to = -1,
        uint64_t seed = 1) {
  ObservationMaker maker(g, seed);
  Tracker tracker;
  const auto cams = walk(g, ascending, speed, 30.0);
  Walk r;
  for (size_t k = 0; k < cams.size(); k += keep) {
    if (static_cast<int>(k) >= gap_from && static_cast<int>(k) < gap_to) continue;
    tracker.update(maker.make(cams[k], static_cast<int64_t>(k) * 33333));
    ++r.frames;
  }
  r.model = tracker.model();
  r.rejected = tracker.rejected_registrations();
  return r;
}

void expect_accurate(const Walk& r, const StairGeometry& g, const char* name) {
  const Accuracy a = score(r.model, g);
  std::printf("[%s] frames %d fused %d rejected %lld: steps %d/%d, false %d, riser %.2f cm, tread %.2f cm\n", name,
              r.frames, r.model.observations_fused, static_cast<long long>(r.rejected), a.matched, a.real_steps,
              a.false_steps, a.riser_abs_cm, a.tread_abs_cm);
  EXPECT_EQ(a.matched, a.real_steps) << name;
  EXPECT_EQ(a.false_steps, 0) << name;
  EXPECT_LE(a.riser_abs_cm, 1.0) << name;
  EXPECT_LE(a.tread_abs_cm, 1.0) << name;
}

// Feeds the walk's frames from its first until the camera reaches `x_m` along the stair (going up
// from below it, going down from above); returns the first frame not fed.
size_t walk_to(Tracker& tracker, ObservationMaker& maker, const std::vector<CameraState>& cams, double x_m) {
  const bool up = cams.back().position_m.x() > cams.front().position_m.x();
  size_t k = 0;
  for (; k < cams.size() && (up ? cams[k].position_m.x() < x_m : cams[k].position_m.x() > x_m); ++k)
    tracker.update(maker.make(cams[k], static_cast<int64_t>(k) * 33333));
  return k;
}

// The published camera's position along the stair from the model's first nosing.
double camera_past_first_nosing_m(const StairModel& m) {
  return m.camera_position_m.x() - m.flights[0].steps[0].nosing_m.x();
}

// Moves everything an observation saw by `off` (a registration gone wrong).
void shift(Observation& obs, const Eigen::Vector3f& off) {
  for (auto& s : obs.steps) s.nosing_m += off.cast<double>();
  for (auto& p : obs.planes) {
    p.centroid += off;
    for (auto& c : p.corners) c += off;
    for (auto& q : p.points) q += off;
  }
}

// Keeps the observation's steps `keep` holds and their planes (a camera looking at a few steps only).
template <typename Keep>
void keep_steps_if(Observation& obs, Keep keep) {
  std::vector<Step> kept;
  for (const Step& s : obs.steps)
    if (keep(s)) kept.push_back(s);
  obs.steps = kept;
  std::vector<Plane> planes;
  for (Step& s : obs.steps)
    for (int* p : {&s.riser_plane, &s.tread_plane})
      if (*p >= 0) {
        planes.push_back(obs.planes[static_cast<size_t>(*p)]);
        *p = static_cast<int>(planes.size()) - 1;
      }
  obs.planes = planes;
}

// Keeps an observation's `n` nearest steps and their planes.
void keep_nearest_steps(Observation& obs, size_t n) {
  size_t k = 0;
  keep_steps_if(obs, [&](const Step&) { return k++ < n; });
}

// Every frame of a 10 Hz walk, in order.
void feed_at_10hz(Tracker& tracker, ObservationMaker& maker, const std::vector<CameraState>& cams) {
  for (size_t k = 0; k < cams.size(); ++k) tracker.update(maker.make(cams[k], static_cast<int64_t>(k) * 100000));
}

// The final model holds every real step and no false one.
void expect_every_real_step(const StairModel& m, const StairGeometry& g) {
  const Accuracy a = score(m, g);
  EXPECT_EQ(a.matched, a.real_steps) << m.status;
  EXPECT_EQ(a.false_steps, 0) << m.status;
}

const StairGeometry kStair = make_stair(9, 0.17, 0.28, 1.5);
const StairGeometry kTwoFlights = make_stair(12, 0.17, 0.28, 1.5, 5, 1.2);

}  // namespace

TEST(TrackerAccuracy, AscendingSlow) { expect_accurate(walk_stair(kStair, true, 0.3), kStair, "up 0.3 m/s"); }
TEST(TrackerAccuracy, AscendingWalking) { expect_accurate(walk_stair(kStair, true, 0.6), kStair, "up 0.6 m/s"); }
TEST(TrackerAccuracy, AscendingWalkingEveryOtherFrame) {
  expect_accurate(walk_stair(kStair, true, 0.6, 2), kStair, "up 0.6 m/s 15 fps");
}
TEST(TrackerAccuracy, AscendingWalkingOneSecondGap) {
  const Walk r = walk_stair(kStair, true, 0.6, 1, 60, 90);
  expect_accurate(r, kStair, "up 0.6 m/s 1 s gap");
}
TEST(TrackerAccuracy, DescendingSlow) { expect_accurate(walk_stair(kStair, false, 0.3), kStair, "down 0.3 m/s"); }
TEST(TrackerAccuracy, DescendingWalking) { expect_accurate(walk_stair(kStair, false, 0.6), kStair, "down 0.6 m/s"); }
TEST(TrackerAccuracy, DescendingWalkingOneSecondGap) {
  expect_accurate(walk_stair(kStair, false, 0.6, 1, 40, 70), kStair, "down 0.6 m/s 1 s gap");
}
TEST(TrackerAccuracy, TwoFlightsAscending) {
  const Walk r = walk_stair(kTwoFlights, true, 0.6);
  expect_accurate(r, kTwoFlights, "two flights up 0.6 m/s");
  ASSERT_EQ(r.model.flights.size(), 2u);
  EXPECT_TRUE(r.model.flights[0].steps.back().landing);
}
TEST(TrackerAccuracy, TwoFlightsDescending) {
  expect_accurate(walk_stair(kTwoFlights, false, 0.6), kTwoFlights, "two flights down 0.6 m/s");
}

TEST(Tracker, CameraOnTheStair) {
  ObservationMaker maker(kStair, 3);
  Tracker tracker;
  const auto cams = walk(kStair, true, 0.6, 30.0);
  int checked = 0;
  for (size_t k = 0; k < cams.size(); ++k) {
    const StairModel& m = tracker.update(maker.make(cams[k], static_cast<int64_t>(k) * 33333));
    if (!m.camera_valid || m.flights.empty() || m.flights[0].steps.size() < kStair.riser_m.size() - 1) continue;
    // Once the model holds the bottom step its frame is the real one.
    if (std::abs(m.flights[0].steps[0].nosing_m.z() - kStair.nosing_z(0)) > 0.02) continue;
    const Eigen::Vector3d& c = cams[k].position_m;
    EXPECT_NEAR(m.camera_position_m.x(), c.x(), 0.03) << k;
    EXPECT_NEAR(m.camera_position_m.z(), c.z(), 0.03) << k;
    // Away from the risers, where the step beneath is unambiguous:
    if (std::abs(std::fmod(c.x() + 10 * 0.28, 0.28)) > 0.03 && std::abs(std::fmod(c.x() + 10 * 0.28, 0.28)) < 0.25) {
      int real = -1;
      while (real + 1 < static_cast<int>(kStair.riser_m.size()) && kStair.nosing_x(real + 1) <= c.x()) ++real;
      EXPECT_EQ(m.camera_step_index, real) << k;
      EXPECT_NEAR(m.camera_height_m, c.z() - kStair.surface_z(c.x()), 0.03) << k;
    }
    ++checked;
  }
  EXPECT_GT(checked, 20);
}

// A tread's plane measures its height; a nosing seen without one (a riser's top,
// under a nosing overhang the slab's underside 5 cm low) only stands in until a
// plane is seen, however often it is seen after.
TEST(TrackerMerge, ATreadPlaneSetsAStepsHeightOverItsEdges) {
  StairMap map;
  const Pose4 pose;
  const TrackerConfig c;
  ObservedStep edge;
  edge.nosing_m = {1.0, 0.0, 0.13};
  ObservedStep plane;
  plane.nosing_m = {1.0, 0.0, 0.18};
  plane.tread_z_m = 0.18;
  merge(map, {edge}, pose, c.merge, c.stair, c.registration.icp_min_distance_m);
  ASSERT_EQ(map.steps.size(), 1u);
  EXPECT_NEAR(map.steps[0].z(), 0.13, 1e-9);
  // One plane is no measurement yet (a sliver seen at a grazing angle set a
  // robot's step 4.5 cm low against 96 edges): the edges stand.
  merge(map, {plane}, pose, c.merge, c.stair, c.registration.icp_min_distance_m);
  for (int k = 0; k < 5; ++k) merge(map, {edge}, pose, c.merge, c.stair, c.registration.icp_min_distance_m);
  ASSERT_EQ(map.steps.size(), 1u);
  EXPECT_NEAR(map.steps[0].z(), 0.13, 1e-9);
  ASSERT_EQ(c.merge.min_tread_plane_observations, 2);
  merge(map, {plane}, pose, c.merge, c.stair, c.registration.icp_min_distance_m);
  for (int k = 0; k < 5; ++k) merge(map, {edge}, pose, c.merge, c.stair, c.registration.icp_min_distance_m);
  ASSERT_EQ(map.steps.size(), 1u);
  EXPECT_NEAR(map.steps[0].z(), 0.18, 1e-9);
  EXPECT_EQ(map.steps[0].confirmations, 13);
}

// A riser stands where perception placed its face, its box's corners (the median of its middle
// rows), not at the mean of its cells: under a nosing overhang the slab's front pulls that mean
// forward by as much of the slab as the view held.
TEST(TrackerMerge, ARiserStandsAtItsBoxsFaceNotItsCentroid) {
  Observation obs;
  Plane riser;
  riser.kind = PlaneKind::Riser;
  for (auto& corner : riser.corners) corner = Eigen::Vector3f(1.23f, 0.0f, -0.7f);
  riser.centroid = Eigen::Vector3f(1.224f, 0.0f, -0.7f);
  obs.planes.push_back(riser);
  Step step;
  step.riser_plane = 0;
  step.nosing_m = Eigen::Vector3d(1.23, 0.0, -0.63);
  obs.steps.push_back(step);
  const std::vector<ObservedStep> observed = observed_steps(obs, Pose4());
  ASSERT_EQ(observed.size(), 1u);
  ASSERT_TRUE(observed[0].riser_x_m.has_value());
  EXPECT_NEAR(*observed[0].riser_x_m, 1.23, 1e-6);
}

TEST(TrackerMerge, ASecondNosingAtAStepsXIsNoNewStep) {
  // A robot looking up at risers under nosing overhangs sees a riser's top
  // where the slab begins, 5-10 cm below its nosing. Beside the same step
  // measured right, that low nosing rises enough above the step below to pass
  // for a step of its own, at the same x: a duplicate step (a Kinect v2 robot
  // ascent had two). One riser has one nosing.
  StairMap map;
  const Pose4 pose;
  const TrackerConfig c;
  auto at = [](double x, double z) {
    ObservedStep o;
    o.nosing_m = {x, 0.0, z};
    return o;
  };
  merge(map, {at(0.0, 0.17), at(0.28, 0.34), at(0.56, 0.51)}, pose, c.merge, c.stair,
        c.registration.icp_min_distance_m);
  ASSERT_EQ(map.steps.size(), 3u);
  EXPECT_EQ(merge(map, {at(0.28, 0.34), at(0.275, 0.245)}, pose, c.merge, c.stair, c.registration.icp_min_distance_m),
            0);
  EXPECT_EQ(map.steps.size(), 3u);
  // A step the model missed, a tread along, is still added.
  EXPECT_EQ(merge(map, {at(0.84, 0.68)}, pose, c.merge, c.stair, c.registration.icp_min_distance_m), 1);
}

// Four steps (rise 0.17 m, run 0.28 m), each tread seen to where the next riser stands, `half_width_m`
// either side of the flight's middle where given; `map` holds them merged three times.
std::vector<ObservedStep> four_steps_merged(StairMap& map, const TrackerConfig& c, std::optional<double> half_width_m = {}) {
  std::vector<ObservedStep> steps;
  for (int k = 0; k < 4; ++k) {
    ObservedStep o;
    o.nosing_m = {0.28 * k, 0.0, 0.17 * (k + 1)};
    o.riser_x_m = 0.28 * k;
    o.tread_z_m = 0.17 * (k + 1);
    o.tread_far_x_m = 0.28 * (k + 1);
    if (half_width_m) o.y_min_m = -*half_width_m, o.y_max_m = *half_width_m;
    steps.push_back(o);
  }
  for (int n = 0; n < 3; ++n) merge(map, steps, Pose4{}, c.merge, c.stair, c.registration.icp_min_distance_m);
  return steps;
}

// The next step's riser stands on the model's top level with its foot inside the model's extent
// (the top tread is taken to run a tread on, and the next riser stands just there). It agrees and
// disagrees with nothing: a Kinect v2 ascent under nosing overhangs, the next riser the only one
// segmented in view, had every registration rejected, and a whole-step search then fitted that
// riser onto the top step (a step lost from the model).
TEST(TrackerRegistration, TheNextStepsRiserIsNoDisagreement) {
  StairMap map;
  const Pose4 pose;
  const TrackerConfig c;
  const std::vector<ObservedStep> steps = four_steps_merged(map, c);
  ASSERT_EQ(map.steps.size(), 4u);
  RegistrationInput in;
  for (const ObservedStep& o : steps) in.nosings.push_back(o.nosing_m);
  for (double y = -0.3; y <= 0.3; y += 0.05)
    for (double z = 0.69; z < 0.85; z += 0.01) in.riser_points.emplace_back(4 * 0.28, y, z);
  const Registration reg = register_to_map(in, map, pose, c.registration, c.stair);
  EXPECT_GE(reg.inlier_ratio, c.motion.min_inlier_ratio);
  EXPECT_NEAR(reg.pose.t_m.x(), 0.0, 0.01);
  // The same riser half a tread short of there, on the part of the top tread the model saw, disagrees.
  for (auto& q : in.riser_points) q.x() -= 0.14;
  EXPECT_LT(register_to_map(in, map, pose, c.registration, c.stair).inlier_ratio, c.motion.min_inlier_ratio);
}

// The model is the flight's profile along the stair; the floor beside an open-sided flight runs on
// under its treads at the floor's height, and is no disagreement: a D435 robot whose body pitched up
// at a flight's foot saw more of that floor, 170 of its 300 tread points disagreed, every
// registration was rejected for 2.8 s and the model was lost (then put two steps back). The
// same level within the flight's width, under its treads, disagrees.
TEST(TrackerRegistration, TheFloorBesideAnOpenSidedFlightIsNoDisagreement) {
  StairMap map;
  const Pose4 pose;
  const TrackerConfig c;
  const std::vector<ObservedStep> steps = four_steps_merged(map, c, 0.45);  // a flight 0.9 m wide
  ASSERT_EQ(map.steps.size(), 4u);
  RegistrationInput in;
  for (const ObservedStep& o : steps) in.nosings.push_back(o.nosing_m);
  for (int k = 0; k < 4; ++k)
    for (double x = 0.28 * k + 0.02; x < 0.28 * (k + 1) - 0.02; x += 0.04)
      for (double y = -0.4; y <= 0.4; y += 0.04) in.tread_points.emplace_back(x, y, 0.17 * (k + 1));
  const size_t on_treads = in.tread_points.size();
  // The floor beside the flight, along it from its first riser to beyond its top step.
  for (double x = -0.1; x < 1.2; x += 0.04)
    for (double y = 0.6; y <= 2.0; y += 0.04) in.tread_points.emplace_back(x, y, 0.0);
  ASSERT_GT(in.tread_points.size(), 2 * on_treads);
  const Registration reg = register_to_map(in, map, pose, c.registration, c.stair);
  EXPECT_GE(reg.inlier_ratio, c.motion.min_inlier_ratio);
  EXPECT_NEAR(reg.pose.t_m.x(), 0.0, 0.01);
  EXPECT_NEAR(reg.pose.t_m.z(), 0.0, 0.01);
  // A level at the floor's height within the flight's width, under its treads: the observation
  // disagrees.
  in.tread_points.resize(on_treads);
  for (double x = 0.02; x < 1.1; x += 0.04)
    for (double y = -0.4; y <= 0.4; y += 0.02) in.tread_points.emplace_back(x, y, 0.0);
  EXPECT_LT(register_to_map(in, map, pose, c.registration, c.stair).inlier_ratio, c.motion.min_inlier_ratio);
}

// A landing between two flights seen only at its ends (a robot looking up from the first flight sees
// the second one beyond the landing's grazing top): a riser standing on it more than a tread short of
// the model's next one is a step the model does not have yet, and agrees and disagrees with nothing.
// The second flight's first riser, not yet in the model, had every registration of a D435 robot
// rejected, and a whole-step search then fitted the observation a step up (2 false model steps).
TEST(TrackerRegistration, ARiserOnAnUnseenPartOfALandingIsNoDisagreement) {
  StairMap map;
  const Pose4 pose;
  const TrackerConfig c;
  std::vector<ObservedStep> steps;
  // Three steps, the third a landing seen 30 cm deep, then three more 1.2 m on.
  const double xs[] = {0.0, 0.28, 0.56, 1.76, 2.04, 2.32};
  for (int k = 0; k < 6; ++k) {
    ObservedStep o;
    o.nosing_m = {xs[k], 0.0, 0.17 * (k + 1)};
    o.riser_x_m = xs[k];
    o.tread_z_m = 0.17 * (k + 1);
    o.tread_far_x_m = k == 2 ? xs[k] + 0.3 : xs[k] + 0.28;
    steps.push_back(o);
  }
  for (int n = 0; n < 3; ++n) merge(map, steps, pose, c.merge, c.stair, c.registration.icp_min_distance_m);
  ASSERT_EQ(map.steps.size(), 6u);
  RegistrationInput in;
  for (int k = 3; k < 6; ++k) in.nosings.push_back(steps[k].nosing_m);
  // The second flight's first riser, a tread before the model's: on the landing's unseen part.
  for (double y = -0.3; y <= 0.3; y += 0.05)
    for (double z = 0.52; z < 0.67; z += 0.01) in.riser_points.emplace_back(1.48, y, z);
  const Registration reg = register_to_map(in, map, pose, c.registration, c.stair);
  EXPECT_GE(reg.inlier_ratio, c.motion.min_inlier_ratio);
  EXPECT_NEAR(reg.pose.t_m.x(), 0.0, 0.01);
  // The same riser on the part of the landing the model saw disagrees.
  for (auto& q : in.riser_points) q.x() = 0.56 + 0.2;
  EXPECT_LT(register_to_map(in, map, pose, c.registration, c.stair).inlier_ratio, c.motion.min_inlier_ratio);
}

TEST(Tracker, StepsCountConfirmations) {
  const Walk r = walk_stair(kStair, true, 0.6);
  for (const auto& f : r.model.flights)
    for (const auto& s : f.steps) EXPECT_GE(s.confirmations, 2);
  EXPECT_GT(r.model.flights[0].steps[0].confirmations, 10);
  EXPECT_GT(r.model.registration_inlier_ratio, 0.5);
  EXPECT_GT(r.model.registration_rmse_m, 0.0);
  EXPECT_LT(r.model.registration_rmse_m, 0.03);
}

// One odd frame (furniture that fits the grammar once) never makes a model:
// its steps are never published, before or after frames without a stair.
TEST(Tracker, ASingleOddFrameNeverLeavesAStepInTheModel) {
  ObservationMaker maker(kStair, 9);
  Tracker tracker;
  const auto cams = walk(kStair, true, 0.6, 30.0);
  Observation empty;
  empty.camera.valid = true;
  for (int k = 0; k < 5; ++k) {
    empty.source_utime = k * 33333;
    EXPECT_TRUE(tracker.update(empty).flights.empty());
  }
  const StairModel& m = tracker.update(maker.make(cams[5], 5 * 33333));
  EXPECT_FALSE(m.confirmed);
  EXPECT_TRUE(m.flights.empty());
  EXPECT_FALSE(m.camera_valid);
  for (int k = 6; k < 60; ++k) {
    empty.source_utime = k * 33333;
    const StairModel& later = tracker.update(empty);
    EXPECT_TRUE(later.flights.empty()) << k;
    EXPECT_FALSE(later.confirmed) << k;
  }
  // Observations that agree confirm it.
  for (int k = 60; k < 63; ++k) tracker.update(maker.make(cams[k], k * 33333));
  EXPECT_TRUE(tracker.model().confirmed);
  EXPECT_FALSE(tracker.model().flights.empty());
}

size_t steps_in(const StairModel& m) {
  size_t n = 0;
  for (const auto& f : m.flights) n += f.steps.size();
  return n;
}

// A flight's next step comes into view a frame before a second frame can confirm it: a step that
// continues the confirmed steps a frame registered on goes with that frame's model, saying it was
// seen once, and not with the next unless that one sees it too. A frame that adds a step above the
// top of a confirmed model: published with it (1 confirmation), gone the frame after, not in the
// final model; with min_confirmations_continuing at min_confirmations, never published.
TEST(Tracker, AStepContinuingTheFlightGoesWithTheFrameThatSawItOnly) {
  const auto cams = walk(kStair, true, 0.6, 30.0);
  const size_t real = kStair.riser_m.size();
  auto run = [&](int continuing, size_t& with_odd, size_t& after, int& odd_confirmations, size_t& final_steps) {
    TrackerConfig c;
    c.confirmation.min_confirmations_continuing = continuing;
    Tracker tracker(c);
    ObservationMaker maker(kStair, 5);
    size_t k = 0;
    // Until the model holds every real step (the top one in view).
    for (; k < cams.size() && !(tracker.model().confirmed && steps_in(tracker.model()) == real); ++k)
      tracker.update(maker.make(cams[k], static_cast<int64_t>(k) * 33333));
    ASSERT_LT(k + 2, cams.size());
    Observation odd = maker.make(cams[k], static_cast<int64_t>(k) * 33333);
    ASSERT_GE(odd.steps.size(), 2u);
    Step above = odd.steps.back();  // a step above the top one, on the top landing
    above.nosing_m += Eigen::Vector3d(0.28, 0.0, 0.17);
    above.riser_plane = above.tread_plane = -1;
    odd.steps.push_back(above);
    const StairModel& m = tracker.update(odd);
    with_odd = steps_in(m);
    odd_confirmations = m.flights.back().steps.back().confirmations;
    after = steps_in(tracker.update(maker.make(cams[k + 1], static_cast<int64_t>(k + 1) * 33333)));
    for (k += 2; k < cams.size(); ++k) tracker.update(maker.make(cams[k], static_cast<int64_t>(k) * 33333));
    final_steps = steps_in(tracker.model());
  };
  size_t with_odd = 0, after = 0, final_steps = 0;
  int confirmations = 0;
  run(1, with_odd, after, confirmations, final_steps);
  EXPECT_EQ(with_odd, real + 1);
  EXPECT_EQ(confirmations, 1);
  EXPECT_EQ(after, real);
  EXPECT_EQ(final_steps, real);
  run(2, with_odd, after, confirmations, final_steps);
  EXPECT_EQ(with_odd, real);
  EXPECT_EQ(after, real);
  EXPECT_EQ(final_steps, real);
}

// Dark treads seen from above show nosings only: nothing to register. Where
// the motion prior puts them on the model's steps they are merged; half a
// tread off they would be new steps between the model's, so they are not.
TEST(Tracker, NosingsOnlyAreMergedOnlyWhereTheyLandOnTheModelsSteps) {
  ObservationMaker maker(kStair, 4);
  Tracker tracker;
  const auto cams = walk(kStair, true, 0.6, 30.0);
  for (int k = 0; k < 30; ++k) tracker.update(maker.make(cams[k], k * 33333));
  auto nosings_only = [&](int k) {
    Observation obs = maker.make(cams[k], k * 33333);
    obs.planes.clear();
    for (Step& st : obs.steps) st.riser_plane = st.tread_plane = -1;
    return obs;
  };
  auto model_steps = [&] {
    size_t n = 0;
    for (const auto& f : tracker.model().flights) n += f.steps.size();
    return n;
  };
  const size_t steps = model_steps();
  ASSERT_GT(steps, 0u);
  Observation on = nosings_only(30);
  ASSERT_FALSE(on.steps.empty());
  const int before = tracker.model().observations_fused;
  const int fused = tracker.update(on).observations_fused;
  EXPECT_EQ(fused, before + 1);  // on the model's steps: merged
  Observation off = nosings_only(31);
  shift(off, Eigen::Vector3f(0.14f, 0.0f, 0.0f));
  const StairModel& m = tracker.update(off);
  EXPECT_NE(m.status.find("not merged"), std::string::npos) << m.status;
  EXPECT_EQ(m.observations_fused, fused);
  EXPECT_EQ(model_steps(), steps);
  EXPECT_TRUE(m.camera_valid);  // the prior still places the camera
}

// Nosings alone, where perception fitted no plane (a level camera sees a descent's far treads as
// slivers), fix the camera along the stair and its height: every frame after the seed carries only its
// nosings. Placed by the motion prior instead, the second frame went in where the seed was (no
// velocity yet), and the camera never moved again.
TEST(Tracker, NosingsAloneRegisterTheCamera) {
  const auto cams = walk(kStair, true, 0.6, 30.0);
  ObservationMaker maker(kStair, 8);
  Tracker tracker;
  int frames = 0, placed = 0, off = 0;
  double sum = 0.0;
  for (size_t k = 0; k < cams.size(); ++k) {
    Observation obs = maker.make(cams[k], static_cast<int64_t>(k) * 33333);
    if (k > 0) {
      obs.planes.clear();
      for (Step& st : obs.steps) st.riser_plane = st.tread_plane = -1;
    }
    const StairModel& m = tracker.update(obs);
    if (k == 0 || m.flights.empty() || cams[k].position_m.x() > kStair.nosing_x(kStair.riser_m.size() - 1)) continue;
    ++frames;
    if (!m.camera_valid) continue;
    ++placed;
    const double e = std::abs(camera_past_first_nosing_m(m) - (cams[k].position_m.x() - kStair.nosing_x(0)));
    sum += e;
    off += e > 0.03;  // a nosing is located to 8 mm (standard deviation) in each frame
  }
  EXPECT_GT(frames, 50);
  EXPECT_GE(placed, frames * 9 / 10);
  EXPECT_EQ(off, 0) << "of " << placed;
  EXPECT_LT(sum / std::max(placed, 1), 0.01);
}

// After a gap the prior's position along the stair is stale, and treads fix
// only the height: a relocalisation on which no riser or nosing agrees is
// rejected (a mid landing fitted the next flight 0.7 m short, onto the last).
TEST(Tracker, ARelocalisationMustRestOnRisersOrNosings) {
  ObservationMaker maker(kStair, 6);
  Tracker tracker;
  const auto cams = walk(kStair, true, 0.6, 30.0);
  for (int k = 0; k < 30; ++k) tracker.update(maker.make(cams[k], k * 33333));
  // Treads only, the nosings lifted far above the model: nothing fixes x.
  Observation obs = maker.make(cams[45], 45 * 33333);
  for (Step& st : obs.steps) {
    st.riser_plane = -1;
    st.nosing_m.z() += 3.0;
  }
  const int64_t rejected = tracker.rejected_registrations();
  const int fused = tracker.model().observations_fused;
  const StairModel& m = tracker.update(obs);
  EXPECT_NE(m.status.find("position along the stair unknown"), std::string::npos) << m.status;
  EXPECT_EQ(tracker.rejected_registrations(), rejected + 1);
  EXPECT_EQ(m.observations_fused, fused);
  // The same frame with its risers relocalises.
  const StairModel& ok = tracker.update(maker.make(cams[46], 46 * 33333));
  EXPECT_EQ(ok.observations_fused, fused + 1) << ok.status;
}

// A level as perception sees it, `rise_below` under the lowest step's nosing:
// going down beyond that step (the floor at a flight's foot), going up before
// it, from `gap` short of its riser to `depth_m` back.
void add_level(Observation& obs, double rise_below, double gap = 0.02, double depth_m = 1.5) {
  const Step* low = &obs.steps.front();
  for (const Step& s : obs.steps)
    if (s.nosing_m.z() < low->nosing_m.z()) low = &s;
  const Eigen::Vector3f n = low->nosing_m.cast<float>();
  const float sign = obs.direction == Direction::Down ? 1.0f : -1.0f;
  const int rows = static_cast<int>(std::lround(depth_m / 0.075));
  Plane p;
  p.kind = PlaneKind::Landing;
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < 10; ++j)
      p.points.emplace_back(n.x() + sign * (static_cast<float>(gap) + 0.075f * i), -0.5f + 0.1f * j,
                            n.z() - static_cast<float>(rise_below));
  p.centroid = Eigen::Vector3f(n.x() + sign * (static_cast<float>(gap) + 0.075f * 0.5f * (rows - 1)), 0.0f,
                               n.z() - static_cast<float>(rise_below));
  p.extent_m = static_cast<float>(depth_m);
  p.support = static_cast<int>(p.points.size());
  obs.planes.push_back(p);
}
void add_floor_beyond_lowest_step(Observation& obs) { add_level(obs, 0.17); }

// A robot tipping over a nosing moves its camera half a step in one frame,
// beyond ICP's reach from the constant-velocity prior. Going down only the
// nosings fix the position along the stair, and a shift by a whole step fits
// them as well: the floor at the flight's foot tells the two apart. The camera
// was placed one step up for the rest of a robot's descent.
TEST(Tracker, AJumpOfHalfAStepDownTheFlightIsPlacedByTheFloorAtItsFoot) {
  ObservationMaker maker(kStair, 8);
  Tracker tracker;
  const auto cams = walk(kStair, false, 0.3, 30.0);
  // Down to above step 5, the foot in view from the start.
  size_t k = 0;
  for (; cams[k].position_m.x() > kStair.nosing_x(5) + 0.1; ++k) {
    Observation obs = maker.make(cams[k], static_cast<int64_t>(k) * 33333);
    if (!obs.steps.empty()) add_floor_beyond_lowest_step(obs);
    tracker.update(obs);
  }
  ASSERT_EQ(tracker.model().flights.size(), 1u);
  ASSERT_EQ(tracker.model().flights[0].steps.size(), kStair.riser_m.size()) << tracker.model().status;
  // Half a tread (14 cm) further down in one frame; the prior expects 1 cm.
  const size_t jump = k + 14;
  Observation obs = maker.make(cams[jump], static_cast<int64_t>(k) * 33333);
  add_floor_beyond_lowest_step(obs);
  const StairModel& m = tracker.update(obs);
  ASSERT_TRUE(m.camera_valid) << m.status;
  const Eigen::Vector3d& c = cams[jump].position_m;
  const double z0 = m.flights[0].steps[0].nosing_m.z() - kStair.nosing_z(0);  // the model's frame vs the stair's
  EXPECT_NEAR(camera_past_first_nosing_m(m), c.x() - kStair.nosing_x(0), 0.04) << m.status;
  EXPECT_NEAR(m.camera_position_m.z() - z0, c.z(), 0.04) << m.status;
}

// A flight that only comes into view from the mid landing (a turn, a wall) after a gap long
// enough to lose the camera: its steps lie beyond the model, and only the landing the camera
// stands on overlaps it. The landing fixes the height and nothing fixes the position along the
// stair but the motion prior; a whole-step search around the last pose instead fitted the new
// flight onto the last one (it is its copy): 4 false model steps on a hand-held two-flight walk.
TEST(Tracker, TheNextFlightSeenFromALandingAfterAGapIsPlacedBeyondIt) {
  // Until then the first flight and the near 0.7 m of its landing are all there is to see.
  const StairGeometry first = make_stair(6, 0.17, 0.28, 0.7);
  ObservationMaker before(first, 12), after(kTwoFlights, 12);
  Tracker tracker;
  const auto cams = walk(kTwoFlights, true, 0.6, 30.0);
  const double landing_x = kTwoFlights.nosing_x(5);
  size_t k = walk_to(tracker, before, cams, landing_x - 0.5);
  ASSERT_EQ(tracker.model().flights.size(), 1u);
  ASSERT_EQ(tracker.model().flights[0].steps.size(), 6u) << tracker.model().status;
  // 0.8 s without a frame: lost, the motion prior still fresh; then the next flight with the
  // landing before it.
  for (k += 24; k < cams.size(); ++k) {
    Observation obs = after.make(cams[k], static_cast<int64_t>(k) * 33333);
    if (!obs.steps.empty() && cams[k].position_m.x() < kTwoFlights.nosing_x(6)) add_level(obs, 0.17, 0.02, 0.45);
    tracker.update(obs);
  }
  Walk r;
  r.model = tracker.model();
  r.frames = static_cast<int>(cams.size()) - 24;
  r.rejected = tracker.rejected_registrations();
  expect_accurate(r, kTwoFlights, "second flight first seen from the landing after a gap");
}

// A frame that shows nothing of the model (the next flight only: a robot's body pitching up at a
// flight's foot, its camera swung 2 cm back against the prior) is merged where the prior puts it,
// its steps as far off the flight before them as the prior was (5.3 cm here, with the robot's rocking).
// Registered on that flight from then on, the camera stays as far off along the first one (a robot
// on two flights: 5.3 cm, the step beneath it wrong at every nosing for 13 s): near a nosing of the
// first flight its step beneath is unknown. The first frame that sees both flights measures the
// offset and the model's second flight moves by it.
TEST(Tracker, AFlightThePriorPlacedMovesToWhereAFrameSeeingBothFlightsPutsIt) {
  // Nine steps to the mid landing: from the first flight's third tread the camera still sees
  // several of its steps beyond the next flight's first two.
  const StairGeometry g = make_stair(14, 0.17, 0.28, 1.5, 8, 1.2);
  const size_t landing = 8;
  ObservationMaker maker(g, 12);
  Tracker tracker;
  // A robot at 10 Hz, its camera 1.75 m up, whose body rocks 3 cm back and forth along the stair.
  auto cams = walk(g, true, 0.3, 10.0);
  for (size_t j = 0; j < cams.size(); ++j) {
    cams[j].position_m.x() += 0.03 * std::sin(2 * M_PI * j / 8.0);
    cams[j].position_m.z() += 0.3;
  }
  const double split_x = g.nosing_x(landing) + 0.6;  // mid landing
  // Steps of one flight only: stair-frame x from the camera's (heading 0: x forward).
  const auto only = [&](Observation& obs, const CameraState& cam, bool second) {
    keep_steps_if(obs, [&](const Step& s) { return (s.nosing_m.x() + cam.position_m.x() > split_x) == second; });
    if (obs.steps.size() < 2) keep_steps_if(obs, [](const Step&) { return false; });
  };
  size_t k = 0;
  for (; k < cams.size() && cams[k].position_m.x() < g.nosing_x(2); ++k) {
    Observation obs = maker.make(cams[k], static_cast<int64_t>(k) * 100000);
    only(obs, cams[k], false);
    tracker.update(obs);
  }
  ASSERT_EQ(tracker.model().flights.size(), 1u) << tracker.model().status;
  // Its body pitches up: the camera swings 2 cm back and sees only the next flight for 1 s.
  for (size_t j = k; j < cams.size(); ++j) cams[j].position_m.x() -= 0.02;
  int second_only = 0, known = 0;
  for (; second_only < 10 && k < cams.size(); ++k) {
    Observation obs = maker.make(cams[k], static_cast<int64_t>(k) * 100000);
    only(obs, cams[k], true);
    second_only += obs.steps.empty() ? 0 : 1;
    const StairModel& m = tracker.update(obs);
    // Registered on the second flight, the camera is as far off along the first as the prior was:
    // within that of a nosing of the first, the step beneath it is unknown, not a guess.
    int truth = -1;
    while (truth + 1 < static_cast<int>(g.riser_m.size()) && cams[k].position_m.x() >= g.nosing_x(static_cast<size_t>(truth + 1)))
      ++truth;
    known += m.camera_beneath_known ? 1 : 0;
    if (m.camera_beneath_known) {
      EXPECT_EQ(m.camera_step_index, truth) << k;
    }
  }
  ASSERT_EQ(second_only, 10);
  EXPECT_GE(known, 3);
  ASSERT_EQ(tracker.model().flights.size(), 2u) << tracker.model().status;
  const auto camera_error_m = [&](const StairModel& m, size_t at) {
    return camera_past_first_nosing_m(m) - (cams[at].position_m.x() - g.nosing_x(0));
  };
  const double off_before_m = camera_error_m(tracker.model(), k - 1);
  // Then both flights in view for 0.5 s.
  for (const size_t end = k + 5; k < end; ++k) tracker.update(maker.make(cams[k], static_cast<int64_t>(k) * 100000));
  const StairModel& m = tracker.model();
  ASSERT_TRUE(m.camera_valid) << m.status;
  ASSERT_EQ(m.flights.size(), 2u) << m.status;
  EXPECT_NEAR(camera_error_m(m, k - 1), 0.0, 0.015) << m.status;
  const Step& mid = m.flights[0].steps.back();
  ASSERT_TRUE(mid.landing);
  const double landing_m = m.flights[1].steps[0].nosing_m.x() - mid.nosing_m.x();
  std::printf("camera %.1f cm off along the first flight with only the second in view, %.1f cm once both were; "
              "landing %.3f m (real %.3f m)\n",
              100 * off_before_m, 100 * camera_error_m(m, k - 1), landing_m, g.tread_m[landing]);
  EXPECT_NEAR(landing_m, g.tread_m[landing], 0.015);
}

// A step a registered frame inserts right before a link the prior placed belongs to the part the
// frame was registered on: beyond the link where its steps lie beyond it (it saw nothing before the
// link, or the link would have been closed), else before it. A robot saw the next flight's first
// step only after its others; left before the link, the next frame measured the link against that
// step alone, closed it 1.5 cm "off", and the camera stayed 6.7 cm off along the first flight.
TEST(TrackerPriorLinks, AStepInsertedBeforeALinkJoinsThePartItsFrameWasRegisteredOn) {
  const auto make_map = [] {
    StairMap map;
    for (int k = 0; k < 6; ++k) {
      MapStep s;
      s.riser_x_m.add(0.25 * k + (k >= 3 ? 1.0 : 0.0), 1);  // a landing after the third step
      s.tread_z_m.add(0.17 * (k + 1), 1);
      s.confirmations = 5;
      map.steps.push_back(s);
    }
    map.steps[3].prior_link_m = 0.08;  // the second flight, placed by the prior
    // The last merge inserted the second flight's first step, on the landing before it.
    MapStep first;
    first.riser_x_m.add(1.5, 1);
    first.tread_z_m.add(0.17 * 3.5, 1);
    first.confirmations = 1;
    first.last_merge = map.merges = 7;
    map.steps.insert(map.steps.begin() + 3, first);
    return map;
  };
  StairMap beyond = make_map();
  extend_prior_links(beyond, 2.0);  // the frame's steps: the second flight's
  EXPECT_DOUBLE_EQ(beyond.steps[3].prior_link_m, 0.08);
  EXPECT_DOUBLE_EQ(beyond.steps[4].prior_link_m, 0.0);
  // Relative to the second flight's steps, the first flight's lie 8 cm uncertain, its own not.
  const std::vector<double> link_m = prior_link_uncertainties_m(beyond, 2.0);
  ASSERT_EQ(link_m.size(), beyond.steps.size());
  EXPECT_DOUBLE_EQ(link_m[0], 0.08);
  EXPECT_DOUBLE_EQ(link_m[3], 0.0);
  EXPECT_DOUBLE_EQ(link_m[5], 0.0);
  StairMap before = make_map();
  extend_prior_links(before, 0.4);  // the frame's steps: the first flight's
  EXPECT_DOUBLE_EQ(before.steps[3].prior_link_m, 0.0);
  EXPECT_DOUBLE_EQ(before.steps[4].prior_link_m, 0.08);
}

// The level the lowest seen step stands on joins registration only where it
// reaches that step's riser: a table top at the height of the floor, 0.6 m in
// front of a flight, is no floor of it.
TEST(TrackerRegistration, TheFootIsTheLevelThatReachesTheLowestRiser) {
  ObservationMaker maker(kStair, 9);
  const auto cams = walk(kStair, true, 0.6, 30.0);
  Observation obs = maker.make(cams[10], 10 * 33333);
  ASSERT_GE(obs.steps.size(), 2u);
  const RegistrationConfig c;
  EXPECT_EQ(foot_plane(obs, c), -1);
  const size_t planes = obs.planes.size();
  add_level(obs, 0.17, 0.6);
  EXPECT_EQ(foot_plane(obs, c), -1) << "a table top short of the riser";
  add_level(obs, 0.30);
  EXPECT_EQ(foot_plane(obs, c), -1) << "a level 13 cm off";
  const size_t treads = registration_input(obs, c).tread_points.size();
  add_level(obs, 0.17);
  EXPECT_EQ(foot_plane(obs, c), static_cast<int>(planes) + 2);
  EXPECT_GT(registration_input(obs, c).tread_points.size(), treads) << "the floor's points join the treads'";
}

// Before the model's first step the camera stands on what that step stands on,
// and one rise below is all the step's own rise says: a tread lies there when
// the steps before it are hidden (a cluttered flight put a hand-held camera 35 cm
// low over a "floor" that was its second tread). Height and step beneath are
// known there only once a floor was seen under the first step: deeper than any
// tread, and no level in view below it.
TEST(Tracker, BeforeTheFirstStepTheHeightIsKnownOnlyOverASeenFloor) {
  const auto cams = walk(kStair, true, 0.6, 30.0);
  auto run = [&](double floor_below, bool lower_level) {
    ObservationMaker maker(kStair, 10);
    Tracker tracker;
    int known = 0, frames = 0;
    for (size_t k = 0; k < cams.size() && cams[k].position_m.x() < -0.3; ++k) {
      Observation obs = maker.make(cams[k], static_cast<int64_t>(k) * 33333);
      // The floor under the first step, while that step is in view (the maker shows steps from 0.5 m
      // ahead): under the second it would be a level 1.5 m deep at the first tread's height.
      const bool first_in_view = cams[k].position_m.x() < kStair.nosing_x(0) - 0.5;
      if (!obs.steps.empty() && floor_below > 0 && first_in_view) add_level(obs, floor_below);
      if (!obs.steps.empty() && lower_level) add_level(obs, 2 * floor_below + 0.01, 0.5);
      const StairModel& m = tracker.update(obs);
      if (!m.camera_valid) continue;
      ++frames;
      if (!m.camera_beneath_known) continue;
      ++known;
      EXPECT_EQ(m.camera_step_index, -1) << k;
      EXPECT_NEAR(m.camera_height_m, cams[k].position_m.z(), 0.03) << k;
    }
    EXPECT_GT(frames, 20);
    return known;
  };
  EXPECT_EQ(run(0.0, false), 0) << "no level seen under the first step";
  EXPECT_GT(run(0.17, false), 20) << "the floor seen";
  EXPECT_EQ(run(0.17, true), 0) << "a level below it: more steps before, hidden";
}

// A frame without steps (perception refuted them, or none is in view) is placed
// by the motion prior, whose height drifts with every bob of a walker's head:
// the levels in view on the model fix it (x stays the prior's). Frames placed so
// were 2.5 cm off in height on average, registered ones 0.4 cm.
TEST(Tracker, AFrameWithoutStepsTakesItsHeightFromTheLevelsInView) {
  ObservationMaker maker(kStair, 11);
  Tracker tracker;
  const auto cams = walk(kStair, true, 0.6, 30.0);
  const size_t k = walk_to(tracker, maker, cams, kStair.nosing_x(2) + 0.1);
  ASSERT_TRUE(tracker.model().camera_valid);
  CameraState raised = cams[k];
  raised.position_m.z() += 0.06;  // a bob the prior does not know of
  Observation obs = maker.make(raised, static_cast<int64_t>(k) * 33333);
  ASSERT_FALSE(obs.planes.empty());
  obs.steps.clear();
  obs.camera.height_m.reset();
  const StairModel& m = tracker.update(obs);
  ASSERT_TRUE(m.camera_valid) << m.status;
  ASSERT_TRUE(m.camera_beneath_known) << m.status;
  EXPECT_NEAR(m.camera_height_m, raised.position_m.z() - kStair.surface_z(raised.position_m.x()), 0.015) << m.status;
}

// From a flight's last steps perception sees one or two and finds no staircase; the motion prior
// places those frames, and a lurch it does not know of puts the camera over the wrong step near an
// edge. The risers in view fix x on the model (the frame is not merged).
TEST(Tracker, AFrameWithoutStepsIsPlacedByTheRisersInView) {
  ObservationMaker maker(kStair, 12);
  Tracker tracker;
  const auto cams = walk(kStair, true, 0.6, 30.0);
  const size_t k = walk_to(tracker, maker, cams, kStair.nosing_x(3) - 0.03);
  ASSERT_TRUE(tracker.model().camera_valid);
  const int fused = tracker.model().observations_fused;
  CameraState lurched = cams[k];
  lurched.position_m.x() = kStair.nosing_x(3) + 0.03;  // 6 cm beyond where the walk was
  Observation obs = maker.make(lurched, static_cast<int64_t>(k) * 33333);
  obs.steps.clear();
  obs.camera.height_m.reset();
  size_t risers = 0;
  for (const Plane& p : obs.planes) risers += p.kind == PlaneKind::Riser;
  ASSERT_GE(risers, 1u);
  const StairModel& m = tracker.update(obs);
  ASSERT_TRUE(m.camera_valid) << m.status;
  EXPECT_NEAR(m.camera_height_m, lurched.position_m.z() - kStair.surface_z(lurched.position_m.x()), 0.015)
      << m.status << ": the step beneath";
  EXPECT_EQ(m.observations_fused, fused) << "not merged";
}

// With nothing in view the motion prior carries the camera on at the last speed; a climber that
// slows (a robot leaving a flight's last step sped up instead: 7.5 cm past the prior, one step low)
// is then over another step than the prior. Where a nosing lies within how far the prior may be off
// (the speed change seen, and half the largest plausible acceleration times t^2), the step beneath
// is unknown: every step beneath that is published is right.
TEST(Tracker, WhereThePriorMayBeOffByANosingTheStepBeneathIsUnknown) {
  const auto cams = walk(kStair, true, 0.6, 30.0);
  const double decel_mps2 = 0.9, speed_mps = 0.6;  // under motion.max_accel_mps2 (1.0)
  auto run = [&](double max_accel_mps2, int& known, int& wrong) {
    TrackerConfig c;
    c.motion.max_accel_mps2 = max_accel_mps2;
    Tracker tracker(c);
    ObservationMaker maker(kStair, 15);
    const size_t k = walk_to(tracker, maker, cams, kStair.nosing_x(4) - 0.10);
    const StairModel& seen = tracker.model();
    ASSERT_FALSE(seen.flights.empty());
    ASSERT_NEAR(seen.flights[0].steps[0].nosing_m.z(), kStair.nosing_z(0), 0.02) << "the model's frame is the real one";
    known = wrong = 0;
    for (int n = 1; n <= 27; ++n) {  // 0.9 s, within predict_camera_s
      const double t = n / 30.0, t_move = std::min(t, speed_mps / decel_mps2);
      CameraState cam = cams[k];
      cam.position_m.x() += speed_mps * t_move - 0.5 * decel_mps2 * t_move * t_move;
      Observation obs = maker.make(cam, static_cast<int64_t>(k + n) * 33333);
      obs.steps.clear();  // a wall ahead: nothing of the stair in view
      obs.planes.clear();
      obs.camera.height_m.reset();
      const StairModel& m = tracker.update(obs);
      ASSERT_TRUE(m.camera_valid) << n << ": " << m.status;
      // The bound is published (camera_position_uncertainty_m): at least the registration's, growing
      // while the prior alone places it, and where it allows for the deceleration the camera is within it.
      EXPECT_GE(m.camera_position_uncertainty_m, c.registration.position_uncertainty_m + 0.5 * max_accel_mps2 * t * t - 1e-9);
      if (max_accel_mps2 >= decel_mps2) {
        EXPECT_LE(std::abs(camera_past_first_nosing_m(m) - (cam.position_m.x() - kStair.nosing_x(0))),
                  m.camera_position_uncertainty_m) << n;
      }
      if (!m.camera_beneath_known) continue;
      int real = -1;
      while (real + 1 < static_cast<int>(kStair.riser_m.size()) && kStair.nosing_x(real + 1) <= cam.position_m.x()) ++real;
      ++known;
      wrong += m.camera_step_index != real;
    }
  };
  int known = 0, wrong = 0;
  run(TrackerConfig{}.motion.max_accel_mps2, known, wrong);
  EXPECT_EQ(wrong, 0);
  EXPECT_GE(known, 5) << "where no nosing is near the prior, the step beneath stays known";
  run(0.0, known, wrong);
  EXPECT_GT(wrong, 0) << "constant velocity trusted as exact: the wrong step beneath";
}

// Turns everything an observation saw about the vertical through the camera (a stair axis measured
// `deg` off: clutter beside the flight).
void turn(Observation& obs, double deg) {
  const Eigen::Matrix3f R = Eigen::AngleAxisf(static_cast<float>(deg * M_PI / 180.0), Eigen::Vector3f::UnitZ()).toRotationMatrix();
  for (auto& st : obs.steps) st.nosing_m = R.cast<double>() * st.nosing_m;
  for (auto& p : obs.planes) {
    p.normal = R * p.normal;
    p.centroid = R * p.centroid;
    for (auto& c : p.corners) c = R * c;
    for (auto& q : p.points) q = R * q;
  }
}

// On a top landing nothing of the flight is in view: the level beneath fixes the camera's height
// and nothing its position along the stair, so after predict_camera_s the camera was unknown (a
// walker 1.5 s on the landing of logs/up_handheld.lcmlog, 3.5 s on two_flights_up's). The wall
// where the landing ends, seen from registered frames on the way up, places it as a riser would.
// A walker crosses the landing towards the wall for 2.5 s: placed on every frame, within 2 cm,
// over the landing; without the wall it is unknown after predict_camera_s.
TEST(Tracker, OnATopLandingItsEndWallPlacesTheCamera) {
  StairGeometry g = make_stair(9, 0.17, 0.28, 1.8);
  const size_t top = g.riser_m.size() - 1;
  auto run = [&](bool wall, int& frames, int& placed, int& off, int& beneath_wrong, std::string& last_status) {
    g.end_wall = wall;
    Tracker tracker;
    ObservationMaker maker(g, 21);
    auto cams = walk(g, true, 0.6, 30.0);
    const CameraState end = cams.back();
    for (int k = 1; k <= 75; ++k) {  // 2.5 s on at 0.3 m/s, the flight behind
      CameraState c = end;
      c.position_m.x() += 0.3 * k / 30.0;
      cams.push_back(c);
    }
    frames = placed = off = beneath_wrong = 0;
    for (size_t k = 0; k < cams.size(); ++k) {
      const StairModel& m = tracker.update(maker.make(cams[k], static_cast<int64_t>(k) * 33333));
      if (cams[k].position_m.x() < g.nosing_x(top) + 0.4) continue;
      ++frames;
      last_status = m.status;
      if (!m.camera_valid) continue;
      ++placed;
      off += std::abs(camera_past_first_nosing_m(m) - (cams[k].position_m.x() - g.nosing_x(0))) > 0.02;
      beneath_wrong += m.camera_beneath_known && m.camera_step_index != static_cast<int>(top);
    }
  };
  int frames = 0, placed = 0, off = 0, wrong = 0;
  std::string status;
  run(true, frames, placed, off, wrong, status);
  EXPECT_GT(frames, 60);
  EXPECT_EQ(placed, frames) << status;
  EXPECT_EQ(off, 0);
  EXPECT_EQ(wrong, 0);
  EXPECT_NE(status.find("end wall"), std::string::npos) << status;
  run(false, frames, placed, off, wrong, status);
  EXPECT_LT(placed, frames / 2) << "without the wall, nothing places the camera on the landing for long";
}

// A climb of `g` at 0.5 m/s (10 frames a second) up to where no step is in view any more (frame
// `k_wall`), then on `step_m` a frame for `frames` frames, the eye 1.45 m over the surface smoothed
// over 0.8 m. Empty where a step stays in view to the walk's end.
std::vector<CameraState> climb_to_the_end_wall(const StairGeometry& g, int frames, double step_m, size_t& k_wall) {
  const std::vector<CameraState> path = walk(g, true, 0.5, 10.0);
  k_wall = 0;
  for (ObservationMaker probe(g, 1); k_wall < path.size() && !probe.make(path[k_wall], 0).steps.empty();) ++k_wall;
  if (k_wall == path.size()) return {};
  std::vector<CameraState> cams(path.begin(), path.begin() + static_cast<long>(k_wall));
  const CameraState last = cams.back();
  for (int k = 1; k <= frames; ++k) {
    CameraState c = last;
    c.position_m.x() += step_m * k;
    double z = 0;
    for (int j = -4; j <= 4; ++j) z += g.surface_z(c.position_m.x() + 0.1 * j) / 9.0;
    c.position_m.z() = z + 1.45;
    cams.push_back(c);
  }
  return cams;
}

// Near a flight's top a climber sees no step ahead, only the wall where the top landing ends: it
// fixes the camera's position along the stair and not its height. A robot slowing there to a fifth
// while the prior carries it on at its climbing speed is put back along the stair by the wall; its
// height comes back with it, along the stair's slope. Kept at the prior's, it rose 4 cm a frame
// above the camera (20 cm in 2 s on a steep flight).
TEST(Tracker, AnEndWallAloneMovesTheCameraAlongTheStairsSlope) {
  StairGeometry g = make_stair(9, 0.2, 0.24, 1.8);
  g.end_wall = true;
  Tracker tracker;
  ObservationMaker maker(g, 23);
  size_t k_wall = 0;
  const std::vector<CameraState> cams = climb_to_the_end_wall(g, 20, 0.01, k_wall);  // 2 s at 0.1 m/s
  ASSERT_FALSE(cams.empty());
  int on_wall = 0, off = 0;
  for (size_t k = 0; k < cams.size(); ++k) {
    const StairModel& m = tracker.update(maker.make(cams[k], static_cast<int64_t>(k) * 100000));
    if (m.status.find("end wall in view") == std::string::npos || !m.camera_valid) continue;
    ++on_wall;
    const double dz = m.camera_position_m.z() - m.flights[0].steps[0].nosing_m.z() -
                      (cams[k].position_m.z() - g.nosing_z(0));
    // The walk's eye follows the surface smoothed over 0.8 m, the tracker's the mean over a tread:
    // up to 4 cm apart on these 20 cm rises. Kept at the prior's height: 3 cm more each frame.
    if (std::abs(dz) > 0.05) ADD_FAILURE() << "frame " << k << ": height " << dz << " m off, " << m.status;
    off += std::abs(dz) > 0.05;
  }
  EXPECT_GE(on_wall, 10);
  EXPECT_EQ(off, 0);
}

// Past a flight's top a climber sees the top landing's end wall: it fixes the camera's position along
// the stair, and the height is carried along the stair's mean slope. That holds on the flight; at its
// end the carrier's feet, somewhere behind the camera, are still climbing while the camera's x is on
// the landing, by how much nothing says without a mount: hand-held climbers reaching a top landing
// were published 2-8 cm off its height on the end wall alone. The step beneath still holds; the
// height is unknown until a level or a nosing measures it again, or known with a mount.
TEST(Tracker, AHeightTheEndWallAloneCarriesAcrossAFlightsEndIsUnknown) {
  StairGeometry g = make_stair(9, 0.2, 0.24, 1.8);
  g.end_wall = true;
  const size_t top = g.riser_m.size() - 1;
  size_t k_wall = 0;
  // 6 s at 0.2 m/s, over the flight's top onto the landing.
  const std::vector<CameraState> cams = climb_to_the_end_wall(g, 60, 0.02, k_wall);
  ASSERT_FALSE(cams.empty());
  const double pitch_deg = cams.back().pitch_rad * 180.0 / M_PI;
  auto run = [&](const TrackerConfig& config, int& on_wall_past_end, int& height_given, int& step_given) {
    Tracker tracker(config);
    ObservationMaker maker(g, 23);
    on_wall_past_end = height_given = step_given = 0;
    for (size_t k = 0; k < cams.size(); ++k) {
      const StairModel& m = tracker.update(maker.make(cams[k], static_cast<int64_t>(k) * 100000));
      if (k < k_wall) {  // registered on the flight's treads and nosings: measured
        if (m.camera_beneath_known) {
          EXPECT_TRUE(m.camera_height_known) << "frame " << k << ": " << m.status;
        }
        continue;
      }
      if (m.status.find("end wall in view") == std::string::npos || !m.camera_valid) continue;
      if (cams[k].position_m.x() < g.nosing_x(top) + 0.12) continue;  // half a tread past the top nosing
      ++on_wall_past_end;
      height_given += m.camera_beneath_known && m.camera_height_known;
      step_given += m.camera_beneath_known && m.camera_step_index == static_cast<int>(top);
    }
  };
  int on_wall = 0, height = 0, step = 0;
  run(TrackerConfig{}, on_wall, height, step);
  EXPECT_GE(on_wall, 5);
  EXPECT_EQ(height, 0) << "carried across the flight's end without a mount, the height is unknown";
  EXPECT_EQ(step, on_wall) << "the step beneath still holds";
  // A mount says where the carrier's base is: it is what the mean slope carries, and its height holds.
  TrackerConfig mounted;
  mounted.mount.height_m = 1.45f;
  mounted.mount.pitch_deg = static_cast<float>(pitch_deg);
  run(mounted, on_wall, height, step);
  EXPECT_GE(on_wall, 5);
  EXPECT_EQ(height, on_wall);
}

// Moves everything an observation saw `dx_m` along the camera's forward axis (gravity frame).
void shift(Observation& obs, double dx_m) {
  const Eigen::Vector3f d(static_cast<float>(dx_m), 0.0f, 0.0f);
  for (auto& st : obs.steps) st.nosing_m += d.cast<double>();
  for (auto& e : obs.edges) {
    e.start += d;
    e.end += d;
  }
  for (auto& p : obs.planes) {
    p.centroid += d;
    for (auto& c : p.corners) c += d;
    for (auto& q : p.points) q += d;
  }
}

// Perception locates a nosing to about a grid cell (1 cm at 1.3 m), so a registered camera may be
// that far off along the stair: hand-held walks placed it a millimetre from a nosing and over the
// wrong step. A frame whose steps all came out 6 mm near, the camera 3 mm before a nosing: the
// step beneath is unknown, not the next one; 5 cm from any nosing it stays known and right.
TEST(Tracker, WithinTheRegistrationsUncertaintyOfANosingTheStepBeneathIsUnknown) {
  const auto cams = walk(kStair, true, 0.3, 30.0);
  const Noise exact{0.0, 0.0, 0.0, 0.0};
  auto run = [&](double uncertainty_m, double from_nosing_m) {
    TrackerConfig c;
    c.registration.position_uncertainty_m = uncertainty_m;
    Tracker tracker(c);
    ObservationMaker maker(kStair, 17, 400, exact);
    const size_t k = walk_to(tracker, maker, cams, kStair.nosing_x(3) + from_nosing_m);
    CameraState cam = cams[k];
    cam.position_m.x() = kStair.nosing_x(3) + from_nosing_m;
    Observation obs = maker.make(cam, static_cast<int64_t>(k) * 33333);
    shift(obs, -0.006);
    return tracker.update(obs);
  };
  const StairModel near = run(TrackerConfig{}.registration.position_uncertainty_m, -0.003);
  ASSERT_TRUE(near.camera_valid) << near.status;
  EXPECT_EQ(near.status, "ok");
  EXPECT_FALSE(near.camera_beneath_known) << "step " << near.camera_step_index << ", the real one is 2";
  const StairModel exact_trusted = run(0.0, -0.003);
  EXPECT_TRUE(exact_trusted.camera_beneath_known);
  EXPECT_EQ(exact_trusted.camera_step_index, 3) << "a registration trusted as exact: the next step";
  const StairModel clear = run(TrackerConfig{}.registration.position_uncertainty_m, -0.05);
  EXPECT_TRUE(clear.camera_beneath_known);
  EXPECT_EQ(clear.camera_step_index, 2);
}

// One frame whose stair axis is 13 degrees off is within the yaw jump the prior allows (15), so it
// gave the prior a yaw rate: at 10 fps it turned on 2-3 degrees a frame, the right axes that
// followed fell outside the jump around it, and the camera went 38 cm astray (a cluttered D435
// descent: 24 cm). An axis near the last placed pose's yaw is taken too: it stays on the stair.
TEST(Tracker, OneFrameWithAStairAxisOffDoesNotTurnTheCameraAway) {
  ObservationMaker maker(kStair, 16);
  Tracker tracker;
  const auto cams = walk(kStair, false, 0.3, 10.0);  // 10 fps: few poses in the velocity window
  const auto at = [](size_t k) { return static_cast<int64_t>(k) * 100000; };
  size_t k = 0;
  for (; k < cams.size() && cams[k].position_m.x() > kStair.nosing_x(6); ++k) tracker.update(maker.make(cams[k], at(k)));
  ASSERT_EQ(tracker.model().flights.size(), 1u);
  Observation odd = maker.make(cams[k], at(k));
  ASSERT_GE(odd.steps.size(), 2u);
  turn(odd, 13.0);
  tracker.update(odd);
  double worst_m = 0.0;
  int placed = 0;
  for (size_t j = k + 1; j < cams.size() && j < k + 20; ++j) {
    const StairModel& m = tracker.update(maker.make(cams[j], at(j)));
    if (!m.camera_valid || m.flights.empty()) continue;
    ++placed;
    worst_m = std::max(worst_m, std::abs(camera_past_first_nosing_m(m) - (cams[j].position_m.x() - kStair.nosing_x(0))));
  }
  EXPECT_GE(placed, 15);
  EXPECT_LT(worst_m, 0.03) << "along the stair, over the 19 frames after the odd one";
}

// What perception publishes of a frame in which it found no staircase: its steps' nosings only as
// the depth jumps (convex edges across the flight, in every observation), the planes kept.
void as_depth_jumps_only(Observation& obs) {
  for (const Step& st : obs.steps) {
    Edge e;
    e.type = EdgeType::Convex;
    e.source = EdgeSource::DepthJump;
    e.start = (st.nosing_m + Eigen::Vector3d(0, 0.2, 0)).cast<float>();
    e.end = (st.nosing_m - Eigen::Vector3d(0, 0.2, 0)).cast<float>();
    obs.edges.push_back(e);
  }
  obs.steps.clear();
}

// The camera published valid, placed as `how` says, within 2 cm of `c` along the stair.
void expect_placed(const StairModel& m, const char* how, const CameraState& c) {
  EXPECT_TRUE(m.camera_valid) << m.status;
  EXPECT_NE(m.status.find(how), std::string::npos) << m.status;
  EXPECT_NEAR(camera_past_first_nosing_m(m), c.position_m.x() - kStair.nosing_x(0), 0.02) << m.status;
}

// Past a flight's last steps going down perception sees one step, no staircase, and no riser (they
// face away): the tracker placed the camera by the motion prior alone, 4-6 cm off as a robot tipped
// over the last nosing (the wrong step beneath in 3 frames). The nosings' depth jumps place it.
TEST(Tracker, WithoutStepsTheNosingsDepthJumpsPlaceTheCamera) {
  ObservationMaker maker(kStair, 13);
  Tracker tracker;
  const auto cams = walk(kStair, false, 0.3, 30.0);
  const size_t k = walk_to(tracker, maker, cams, kStair.nosing_x(3));
  ASSERT_EQ(tracker.model().flights.size(), 1u);
  // The next frame, but the camera 6 cm on where the prior expects 1 cm.
  const size_t j = k + 6;
  Observation obs = maker.make(cams[j], static_cast<int64_t>(k) * 33333);
  ASSERT_FALSE(obs.steps.empty());
  as_depth_jumps_only(obs);
  expect_placed(tracker.update(obs), "nosings in view", cams[j]);
}

// The motion prior starts from where the camera was last placed: a robot that slowed as it tipped
// over a flight's last nosing was placed on the nosings in view, and the next frame with nothing in
// view was put 12 cm on, extrapolated from the last registration.
TEST(Tracker, ThePriorStartsFromTheLastPlacement) {
  ObservationMaker maker(kStair, 14);
  Tracker tracker;
  const auto cams = walk(kStair, false, 0.3, 30.0);
  const size_t k = walk_to(tracker, maker, cams, kStair.nosing_x(3));
  // Stopped for 10 frames (the prior expects 1 cm each), only the nosings' jumps in view.
  for (int n = 1; n <= 10; ++n) {
    Observation obs = maker.make(cams[k], static_cast<int64_t>(k + n) * 33333);
    as_depth_jumps_only(obs);
    ASSERT_NE(tracker.update(obs).status.find("nosings in view"), std::string::npos) << tracker.model().status;
  }
  Observation nothing = maker.make(cams[k], static_cast<int64_t>(k + 11) * 33333);
  nothing.steps.clear();
  nothing.planes.clear();
  expect_placed(tracker.update(nothing), "motion prior", cams[k]);
}

// Removes the observation's nearest step and its planes (a step the camera did not see).
void drop_nearest_step(Observation& obs) {
  if (obs.steps.empty()) return;
  const Step gone = obs.steps.front();
  obs.steps.erase(obs.steps.begin());
  for (int plane : {std::max(gone.riser_plane, gone.tread_plane), std::min(gone.riser_plane, gone.tread_plane)}) {
    if (plane < 0) continue;
    obs.planes.erase(obs.planes.begin() + plane);
    for (Step& s : obs.steps)
      for (int* index : {&s.riser_plane, &s.tread_plane})
        if (*index > plane) --*index;
  }
}

// Going down, each step hides the back of the tread below it: what is seen of
// that tread is no measurement of its depth. A model whose top step was seen
// only so publishes it without a depth, not with the part in view.
TEST(Tracker, ATreadSeenOnlyInPartIsPublishedWithoutADepth) {
  ObservationMaker maker(kStair, 4);
  Tracker tracker;
  const auto cams = walk(kStair, false, 0.6, 30.0);
  const size_t top = kStair.riser_m.size() - 1;
  int fed = 0;
  for (size_t k = 0; k < cams.size() && cams[k].position_m.x() > kStair.nosing_x(top) + 0.3; ++k, ++fed) {
    Observation obs = maker.make(cams[k], static_cast<int64_t>(k) * 33333);
    drop_nearest_step(obs);  // the top step, hidden from the whole walk
    for (const Step& s : obs.steps) ASSERT_TRUE(s.inferred & kStepTreadPartial);
    tracker.update(obs);
  }
  const StairModel& m = tracker.model();
  ASSERT_GT(fed, 30);
  ASSERT_TRUE(m.confirmed);
  ASSERT_EQ(m.flights.size(), 1u);
  const auto& steps = m.flights[0].steps;
  ASSERT_GE(steps.size(), 3u);
  for (size_t i = 0; i + 1 < steps.size(); ++i) {
    ASSERT_TRUE(steps[i].tread_depth_m) << i;
    EXPECT_NEAR(*steps[i].tread_depth_m, 0.28, 0.01) << i;
  }
  EXPECT_FALSE(steps.back().tread_depth_m) << *steps.back().tread_depth_m << " m published for a tread never seen whole";
  EXPECT_FALSE(steps.back().landing);
}

TEST(Tracker, OutOfOrderObservationsAreDroppedAndCounted) {
  ObservationMaker maker(kStair, 5);
  Tracker tracker;
  const auto cams = walk(kStair, true, 0.6, 30.0);
  for (int k = 0; k < 20; ++k) tracker.update(maker.make(cams[k], k * 33333));
  const int fused = tracker.model().observations_fused;
  const StairModel& m = tracker.update(maker.make(cams[5], 5 * 33333));
  EXPECT_EQ(tracker.dropped_out_of_order(), 1);
  EXPECT_EQ(m.observations_fused, fused);
  tracker.update(maker.make(cams[20], 19 * 33333));  // same utime as the last one
  EXPECT_EQ(tracker.dropped_out_of_order(), 2);
  tracker.update(maker.make(cams[20], 20 * 33333));
  EXPECT_EQ(tracker.model().observations_fused, fused + 1);
}

// Issue 18: a log replayed twice (or a camera restarted) sends time back by
// seconds. That starts a new stream: the model is reset and the second pass is
// tracked like the first, every observation giving a model; a step back
// smaller than time_jump_back_s is reordering and is dropped.
TEST(Tracker, ALogReplayedTwiceIsTrackedBothTimes) {
  ObservationMaker maker(kStair, 7);
  Tracker tracker;
  const auto cams = walk(kStair, true, 0.6, 30.0);
  const int n = 90;
  for (int k = 0; k < n; ++k) tracker.update(maker.make(cams[k], k * 33333));
  const int fused_first = tracker.model().observations_fused;
  ASSERT_GT(fused_first, 60);
  tracker.update(maker.make(cams[n - 5], (n - 20) * 33333));  // 0.5 s back: out of order
  EXPECT_EQ(tracker.dropped_out_of_order(), 1);
  EXPECT_EQ(tracker.time_jumps(), 0);
  for (int k = 0; k < n; ++k) {
    const StairModel& m = tracker.update(maker.make(cams[k], k * 33333));
    if (k == 0) {
      EXPECT_EQ(tracker.time_jumps(), 1);
      EXPECT_EQ(m.observations_fused, 1);
      EXPECT_NE(m.status.find("time went back"), std::string::npos) << m.status;
    }
  }
  EXPECT_EQ(tracker.dropped_out_of_order(), 1) << "nothing of the second pass is dropped";
  EXPECT_EQ(tracker.model().observations_fused, fused_first);
  EXPECT_EQ(tracker.model().state, TrackingState::Ok);
}

TEST(Tracker, EmptyObservationsLoseThenResetTheModel) {
  TrackerConfig c;
  c.lifecycle.lost_after_s = 0.5;
  c.lifecycle.reset_after_s = 2.0;
  ObservationMaker maker(kStair, 6);
  Tracker tracker(c);
  const auto cams = walk(kStair, true, 0.6, 30.0);
  for (int k = 0; k < 15; ++k) tracker.update(maker.make(cams[k], k * 33333));
  ASSERT_EQ(tracker.model().state, TrackingState::Ok);
  ASSERT_FALSE(tracker.model().flights.empty());
  Observation empty;
  empty.camera.valid = true;
  empty.source_utime = 15 * 33333;
  const Eigen::Vector3d last = tracker.model().camera_position_m;
  EXPECT_EQ(tracker.update(empty).state, TrackingState::Ok);
  // No step in view: the camera is placed by the motion prior (0.6 m/s, 33 ms on).
  EXPECT_TRUE(tracker.model().camera_valid);
  EXPECT_NEAR((tracker.model().camera_position_m - last).norm(), 0.02, 0.01);
  empty.source_utime = 14 * 33333 + 1'000'000;
  EXPECT_EQ(tracker.update(empty).state, TrackingState::Lost);
  EXPECT_FALSE(tracker.model().flights.empty());  // lost is not forgotten
  empty.source_utime = 14 * 33333 + 2'100'000;
  EXPECT_EQ(tracker.update(empty).state, TrackingState::Lost);
  EXPECT_FALSE(tracker.model().camera_valid);  // the motion prior is stale (predict_camera_s)
  EXPECT_FALSE(tracker.model().flights.empty());  // kept until a stair is in view again
  EXPECT_EQ(tracker.resets(), 0);
  // A stair in view again after more than reset_after_s: a new model from it.
  const StairModel& m = tracker.update(maker.make(cams[150], 14 * 33333 + 2'200'000));
  EXPECT_EQ(tracker.resets(), 1);
  EXPECT_EQ(m.state, TrackingState::Ok);
  EXPECT_EQ(m.observations_fused, 1);
}

TEST(Tracker, ResetForgetsTheModel) {
  ObservationMaker maker(kStair, 7);
  Tracker tracker;
  const auto cams = walk(kStair, true, 0.6, 30.0);
  for (int k = 0; k < 10; ++k) tracker.update(maker.make(cams[k], k * 33333));
  ASSERT_GT(tracker.model().observations_fused, 0);
  tracker.reset();
  EXPECT_EQ(tracker.model().observations_fused, 0);
  EXPECT_TRUE(tracker.model().flights.empty());
  EXPECT_EQ(tracker.model().state, TrackingState::None);
}

TEST(TrackerConfig, LoadsTheTrackerSectionAndNamesKeysAndRanges) {
  const std::string path = std::string(STAIRS_BINARY_DIR) + "/tracker_config_test.json";
  const auto error = [&](const std::string& text) {
    std::ofstream(path) << text;
    try {
      load_tracker_config(path);
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  std::ofstream(path) << R"({"tracker": {"lifecycle": {"reset_after_s": 3.5}, "confirmation": {"min_confirmations": 3}},
                             "perception": {"stair": {"min_steps": 3}}, "stair": {"landing_min_depth_m": 0.8}})";
  const TrackerConfig c = load_tracker_config(path);
  EXPECT_DOUBLE_EQ(c.stair.landing_min_depth_m, 0.8);  // the top-level key perception reads too
  EXPECT_DOUBLE_EQ(c.lifecycle.reset_after_s, 3.5);
  EXPECT_EQ(c.confirmation.min_confirmations, 3);
  EXPECT_DOUBLE_EQ(c.registration.icp_max_distance_m, 1.0);
  EXPECT_NE(error(R"({"tracker": {"lifecycle": {"reset_after_seconds": 3.5}}})")
                .find("unknown key 'tracker.lifecycle.reset_after_seconds'"),
            std::string::npos);
  EXPECT_NE(error(R"({"tracker": {"confirmation": {"min_confirmations": "two"}}})")
                .find("'tracker.confirmation.min_confirmations' must be an integer"),
            std::string::npos);
  EXPECT_NE(error(R"({"tracker": {"registration": {"icp_min_distance_m": 2.0}}})")
                .find("'tracker.registration.icp_min_distance_m' must be at most"),
            std::string::npos);
  EXPECT_NE(error(R"({"tracker": {"motion": {"min_inlier_ratio": 1.5}}})").find("allowed 0..1"), std::string::npos);
  // A flat file (the layout before the one config file) is refused, naming the key; so is
  // an old flat tracker key, with a hint where the keys went.
  EXPECT_NE(error(R"({"reset_after_s": 3.5})").find("unknown key 'reset_after_s'"), std::string::npos);
  EXPECT_NE(error(R"({"tracker": {"reset_after_s": 3.5}})").find("grouped by concept"), std::string::npos);
  std::remove(path.c_str());
}

// A value set in code (stairs-tracker --reset-after-s) is checked against the same range.
TEST(TrackerConfig, ValidateNamesTheKeyAndTheAllowedRange) {
  TrackerConfig c;
  c.lifecycle.reset_after_s = -1.0;
  try {
    validate(c);
    FAIL() << "a negative reset_after_s was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("'tracker.lifecycle.reset_after_s' = -1 is out of range: allowed 0.001..86400"),
              std::string::npos)
        << e.what();
  }
}

TEST(Tracker, RejectsARegistrationThatJumpsAwayFromTheMotionPrior) {
  ObservationMaker maker(kStair, 8);
  Tracker tracker;
  const auto cams = walk(kStair, true, 0.6, 30.0);
  for (size_t k = 0; k < cams.size(); ++k) {
    Observation obs = maker.make(cams[k], static_cast<int64_t>(k) * 33333);
    if (k == 100 && !obs.steps.empty()) {
      // A whole observation 20 cm off: no camera moves that far in 33 ms.
      shift(obs, Eigen::Vector3f(0.2f, 0.0f, 0.0f));
      const int fused = tracker.model().observations_fused;
      const Eigen::Vector3d before = tracker.model().camera_position_m;
      // The camera stays where the motion prior puts it (0.6 m/s, 33 ms on).
      EXPECT_TRUE(tracker.update(obs).camera_valid);
      EXPECT_LT((tracker.model().camera_position_m - before).norm(), 0.04);
      EXPECT_EQ(tracker.model().observations_fused, fused);
      continue;
    }
    tracker.update(obs);
  }
  EXPECT_EQ(tracker.rejected_registrations(), 1);
  const Accuracy a = score(tracker.model(), kStair);
  EXPECT_EQ(a.matched, a.real_steps);
  EXPECT_EQ(a.false_steps, 0);
}

TEST(Tracker, ABadSeedThatNoLaterObservationConfirmsIsReplaced) {
  ObservationMaker maker(kStair, 8);
  Tracker tracker;
  const auto cams = walk(kStair, true, 0.6, 30.0);
  // The seed is 20 cm off (a poor frame): every later observation disagrees.
  Observation bad = maker.make(cams[20], 20 * 33333);
  ASSERT_GE(bad.steps.size(), 2u);
  shift(bad, Eigen::Vector3f(0.2f, 0.0f, 0.0f));
  EXPECT_EQ(tracker.update(bad).observations_fused, 1);
  // The next one is rejected against that seed and becomes the new seed.
  const StairModel& m = tracker.update(maker.make(cams[21], 21 * 33333));
  EXPECT_EQ(tracker.rejected_registrations(), 1);
  EXPECT_EQ(tracker.resets(), 1);
  EXPECT_EQ(m.state, TrackingState::Ok);
  EXPECT_EQ(m.observations_fused, 1);
  for (size_t k = 22; k < cams.size(); ++k) tracker.update(maker.make(cams[k], static_cast<int64_t>(k) * 33333));
  EXPECT_EQ(tracker.rejected_registrations(), 1);
  const Accuracy a = score(tracker.model(), kStair);
  EXPECT_EQ(a.matched, a.real_steps);
  EXPECT_EQ(a.false_steps, 0);
}

TEST(Tracker, ModelStepsAreCapped) {
  TrackerConfig c;
  c.merge.max_model_steps = 4;
  ObservationMaker maker(kStair, 9);
  Tracker tracker(c);
  const auto cams = walk(kStair, true, 0.6, 30.0);
  for (size_t k = 0; k < cams.size(); ++k) tracker.update(maker.make(cams[k], static_cast<int64_t>(k) * 33333));
  size_t steps = 0;
  for (const auto& f : tracker.model().flights) steps += f.steps.size();
  EXPECT_GE(steps, 2u);
  EXPECT_LE(steps, 4u);
  EXPECT_LE(tracker.model().planes.size(), 8u);
}

TEST(Tracker, StepsFromCameraInTheGravityAlignedFrame) {
  // Camera at (-1, 0.2, 1) in the model frame, heading along +y, 30 deg down:
  // its forward is +y, its left is -x (worked out by hand).
  StairModel m;
  m.camera_valid = true;
  m.camera_position_m = {-1.0, 0.2, 1.0};
  const double p = -30.0 * M_PI / 180.0;
  Eigen::Matrix3d R;
  R.col(0) = Eigen::Vector3d(1, 0, 0);                              // image right
  R.col(1) = Eigen::Vector3d(0, std::sin(p), -std::cos(p));         // image down
  R.col(2) = Eigen::Vector3d(0, std::cos(p), std::sin(p));          // optical axis
  m.camera_orientation = Eigen::Quaterniond(R);
  Step s;
  s.riser_height_m = 0.18;
  s.nosing_m = {0.5, 1.2, 0.36};
  m.flights.resize(2);
  m.flights[1].steps.push_back(s);
  const std::vector<Step> seen = steps_from_camera(m);
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_NEAR(seen[0].nosing_m.x(), 1.0, 1e-9);
  EXPECT_NEAR(seen[0].nosing_m.y(), -1.5, 1e-9);
  EXPECT_NEAR(seen[0].nosing_m.z(), -0.64, 1e-9);
  EXPECT_EQ(*seen[0].riser_height_m, 0.18);
  m.camera_valid = false;
  EXPECT_TRUE(steps_from_camera(m).empty());
}

// A flight has one first step. A robot's camera on a 0.9 m mast swings 20 cm back along the stair
// in a frame as the body rocks over a nosing, farther than the prior's uncertainty lets the
// whole-step search try: ICP from the prior then fits the periodic flight a step off, and near the
// foot of a descent every such frame put the lowest step seen a step below the model's first, on
// the floor the model had seen before it (2 false model steps on a D435 robot's descent). Where
// the floor is seen before the lowest step, that step is the model's first.
TEST(Tracker, AFlightHasOneFirstStepWhereTheFloorIsSeenBeforeIt) {
  StairGeometry stair = make_stair(10, 0.18, 0.25, 1.5);
  stair.floor_depth_m = 2.0;
  ObservationMaker maker(stair, 9);
  Tracker tracker;
  std::vector<CameraState> cams = walk(stair, false, 0.3, 10.0);
  for (size_t k = 0; k < cams.size(); ++k)
    if (k % 4 == 3 && cams[k].position_m.x() < 1.6) cams[k].position_m += Eigen::Vector3d(0.2, 0.0, 0.12);
  feed_at_10hz(tracker, maker, cams);
  expect_every_real_step(tracker.model(), stair);
}

// A robot's camera on a tall mast, its body rocking over the nosings: the camera swings 10 cm
// along the stair and back from one frame to the next, beyond what ICP reaches from a
// constant-velocity prior. Half a step either way then fits the periodic flight as well, and the
// start tried first (a step back) won four frames in a row: the velocity then carried the camera up
// the stair a step a frame while it went down, and the model grew to 44 steps. Of two shifts that
// agree alike, the one nearer the prior is taken.
TEST(Tracker, ACameraRockingAlongTheStairIsNotCarriedAStepAFrame) {
  const StairGeometry stair = make_stair(14, 0.17, 0.28, 1.5);
  ObservationMaker maker(stair, 5);
  Tracker tracker;
  std::vector<CameraState> cams = walk(stair, false, 0.3, 10.0);
  for (size_t k = 0; k < cams.size(); ++k) cams[k].position_m.x() += (k % 2 ? 0.12 : -0.12) * (k > 10);
  feed_at_10hz(tracker, maker, cams);
  expect_every_real_step(tracker.model(), stair);
}

// A robot's body rocks back as it tips over a nosing while the constant-velocity prior carries it
// on. The registration then lies 13 cm behind the prior, beyond the prior's reach, and is not
// merged; placed by the prior instead, the next frame started 21 cm ahead of the camera, nearer the
// next step's alias, and registered a whole step up (a false step). Placed on the registration, the
// next frame starts where the camera is.
TEST(Tracker, ARegistrationBeyondThePriorsReachPlacesTheCameraForTheNextFrame) {
  const StairGeometry stair = make_stair(12, 0.17, 0.28, 1.5);
  ObservationMaker maker(stair, 3);
  Tracker tracker;
  std::vector<CameraState> cams = walk(stair, true, 0.5, 10.0);
  const size_t k = 30;
  // On the flight's lower half, its steps ahead in view.
  ASSERT_GT(cams[k].position_m.x(), stair.nosing_x(0) - 1.0);
  ASSERT_LT(cams[k + 1].position_m.x(), stair.nosing_x(6));
  // 13 cm back at frame k, 18 cm back from k + 1 on (the robot climbs on from there).
  for (size_t j = k; j < cams.size(); ++j) cams[j].position_m.x() -= j == k ? 0.13 : 0.18;
  for (size_t j = 0; j < cams.size(); ++j) {
    const StairModel& m = tracker.update(maker.make(cams[j], static_cast<int64_t>(j) * 100000));
    if (j == k) {
      ASSERT_NE(m.status.find("registration rejected"), std::string::npos) << m.status;
      EXPECT_TRUE(m.camera_valid) << m.status;
      EXPECT_NEAR(camera_past_first_nosing_m(m), cams[k].position_m.x() - stair.nosing_x(0), 0.03) << m.status;
      EXPECT_GE(m.camera_position_uncertainty_m, 0.12) << m.status;
    }
    if (j == k + 1) {
      EXPECT_EQ(m.status, "ok");
      EXPECT_NEAR(camera_past_first_nosing_m(m), cams[k + 1].position_m.x() - stair.nosing_x(0), 0.03) << m.status;
    }
  }
  expect_every_real_step(tracker.model(), stair);
}

// A robot's body pitching up at a flight's foot swings its camera back by more than ICP reaches from
// the prior (a fraction of a tread), and less than half a step. The registration from the prior
// stops short with few points agreeing; turned down frame after frame, the model was lost (2 of a
// flight's steps missing). The whole-step search from half a step either way finds it: taken, as it
// lies within half a step of the prior and no other shift fits as well.
TEST(Tracker, ACameraSwungBackBeyondICPsReachIsFoundByTheSearch) {
  const StairGeometry stair = make_stair(10, 0.17, 0.28, 1.5);
  ObservationMaker maker(stair, 4);
  Tracker tracker;
  std::vector<CameraState> cams = walk(stair, true, 0.3, 10.0);
  size_t k = 0;
  while (k < cams.size() && cams[k].position_m.x() < stair.nosing_x(0) - 1.0) ++k;
  ASSERT_LT(k + 1, cams.size());
  for (size_t j = k; j < cams.size(); ++j) cams[j].position_m.x() -= 0.15;
  for (size_t j = 0; j < cams.size(); ++j) {
    const StairModel& m = tracker.update(maker.make(cams[j], static_cast<int64_t>(j) * 100000));
    if (j == k) {
      EXPECT_EQ(m.status, "relocalised");
      EXPECT_NEAR(camera_past_first_nosing_m(m), cams[k].position_m.x() - stair.nosing_x(0), 0.03) << m.status;
    }
  }
  expect_every_real_step(tracker.model(), stair);
}

// A robot's body rocks 15 cm back over a nosing and the robot then stands for a second while the
// constant-velocity prior carries it on. Turned down frame after frame, the prior ends more than half
// a tread off, and the whole-step search then finds shifts a step apart that fit alike (a uniform
// part of the flight, its ends out of view): the one nearest that prior is a guess (a step up; the
// model gained a step above its top). The camera's position is unknown until a frame tells the
// shifts apart; a camera published as known to within half a tread is never a step off.
TEST(Tracker, AWholeStepShiftARefutedPriorCannotTellApartLeavesThePositionUnknown) {
  StairGeometry stair = make_stair(14, 0.17, 0.28, 1.5);
  stair.floor_depth_m = 2.0;
  ObservationMaker maker(stair, 6);
  Tracker tracker;
  const std::vector<CameraState> path = walk(stair, true, 0.5, 10.0);
  size_t k = 0;
  while (k < path.size() && path[k].position_m.x() < -0.9) ++k;
  ASSERT_LT(k, path.size());
  std::vector<CameraState> cams(path.begin(), path.begin() + static_cast<long>(k));
  for (int j = 0; j < 10; ++j) cams.push_back(path[k]);  // a second standing
  cams.insert(cams.end(), path.begin() + static_cast<long>(k), path.end());
  for (size_t j = k; j < cams.size(); ++j) cams[j].position_m.x() -= 0.2;
  int known = 0, off = 0, unknown = 0;
  for (size_t j = 0; j < cams.size(); ++j) {
    Observation obs = maker.make(cams[j], static_cast<int64_t>(j) * 100000);
    // For 1.5 s from the lurch only the 3 nearest steps are seen (the camera pitched down at them):
    // the model runs on beyond them either way, and shifts a step apart fit them alike. Then the
    // floor before the first step tells them apart again.
    if (j >= k && j < k + 15) keep_nearest_steps(obs, 3);
    const StairModel& m = tracker.update(obs);
    if (j < k || !m.camera_valid || m.flights.empty()) continue;
    if (m.camera_position_uncertainty_m >= 0.14) {
      ++unknown;
      continue;
    }
    ++known;
    const double along = camera_past_first_nosing_m(m) - (cams[j].position_m.x() - stair.nosing_x(0));
    if (std::abs(along) > 0.05) ADD_FAILURE() << "frame " << j << ": " << along << " m off, " << m.status;
    off += std::abs(along) > 0.05;
  }
  EXPECT_GT(unknown, 0) << "the prior was never uncertain: no test";
  EXPECT_GT(known, 20);
  EXPECT_EQ(off, 0);
  expect_every_real_step(tracker.model(), stair);
}

// The whole-step search says when another shift fits about as well as the one it returns: on a
// uniform part of a flight, its ends out of view, the shifts a step apart agree equally; where the
// observation holds an irregular step, only the right shift fits it.
TEST(TrackerRelocalisation, SaysWhenAnotherWholeStepShiftFitsAsWell) {
  StairMap map;
  const TrackerConfig c;
  // Eight steps 28 cm deep, 17 cm high but the fifth (index 4), 23 cm.
  auto z_of = [](int k) { return 0.17 * (k + 1) + (k >= 4 ? 0.06 : 0.0); };
  std::vector<ObservedStep> steps;
  for (int k = 0; k < 8; ++k) {
    ObservedStep o;
    o.nosing_m = {0.28 * k, 0.0, z_of(k)};
    o.riser_x_m = 0.28 * k;
    o.tread_z_m = z_of(k);
    o.tread_far_x_m = 0.28 * (k + 1);
    steps.push_back(o);
  }
  for (int n = 0; n < 3; ++n) merge(map, steps, Pose4{}, c.merge, c.stair, c.registration.icp_min_distance_m);
  ASSERT_EQ(map.steps.size(), 8u);
  // Steps `from`..`to` in view: their risers and nosings.
  auto in_view = [&](int from, int to) {
    RegistrationInput in;
    for (int k = from; k <= to; ++k) {
      in.nosings.push_back(steps[k].nosing_m);
      const double foot = k == 0 ? 0.0 : z_of(k - 1);
      for (double y = -0.3; y <= 0.3; y += 0.1)
        for (double z = foot + 0.02; z < z_of(k) - 0.02; z += 0.02) in.riser_points.emplace_back(0.28 * k, y, z);
    }
    return in;
  };
  Pose4 half_off;
  half_off.t_m = Eigen::Vector3d(0.14, 0.0, 0.085);
  bool ambiguous = false;
  relocalise(in_view(1, 2), map, half_off, c.relocalisation, c.registration, c.stair, 1.0, &ambiguous);
  EXPECT_TRUE(ambiguous);
  Pose4 near;
  near.t_m = Eigen::Vector3d(0.03, 0.0, 0.0);
  const Registration r = relocalise(in_view(3, 5), map, near, c.relocalisation, c.registration, c.stair, 1.0, &ambiguous);
  EXPECT_FALSE(ambiguous);
  EXPECT_NEAR(r.pose.t_m.x(), 0.0, 0.01);
}

// A hand-held descent: the far steps seen first, then 0.6 s without a frame while the walker stood
// still and the constant-velocity prior carried it on 0.36 m, then only the two nearest steps, which
// the model does not hold yet. Nothing of them lies on the model: the prior alone would say where
// along the stair they go, and it may be off by more than half a tread by then (the walker could
// have kept walking, stopped or sped up). Merged where it said, they lay a third of a metre down the flight:
// a false "landing" and 2 false steps. Not merged, the model keeps its far steps and no false one.
TEST(Tracker, StepsNothingOnTheModelPlacesAreNotMergedWhereAnUncertainPriorWouldPutThem) {
  const StairGeometry stair = make_stair(10, 0.17, 0.28, 1.5);
  ObservationMaker maker(stair, 8);
  Tracker tracker;
  const std::vector<CameraState> path = walk(stair, false, 0.6, 10.0);
  ASSERT_GT(path.size(), 30u);
  const auto distance = [](const Step& s) { return s.nosing_m.head<2>().norm(); };
  size_t j = 0;
  for (; j < 5; ++j) {  // walking, the nearest steps out of view (pitched up)
    Observation obs = maker.make(path[j], static_cast<int64_t>(j) * 100000);
    keep_steps_if(obs, [&](const Step& s) { return distance(s) > 2.0; });
    tracker.update(obs);
  }
  ASSERT_FALSE(tracker.model().flights.empty()) << tracker.model().status;
  const CameraState stood = path[j - 1];
  int64_t t_us = static_cast<int64_t>(j - 1) * 100000 + 600000;  // 0.6 s later, not a step on
  for (int k = 0; k < 3; ++k, t_us += 100000) {
    Observation obs = maker.make(stood, t_us);
    keep_steps_if(obs, [&](const Step& s) { return distance(s) < 1.2; });
    ASSERT_GE(obs.steps.size(), 2u);
    const StairModel& m = tracker.update(obs);
    const Accuracy a = score(m, stair);
    EXPECT_EQ(a.false_steps, 0) << "frame " << k << " after the gap: " << m.status;
  }
  const Accuracy a = score(tracker.model(), stair);
  EXPECT_GE(a.matched, 5) << tracker.model().status;
}
