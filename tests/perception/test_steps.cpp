#include "perception/grammar.hpp"
#include "perception/normals.hpp"
#include "perception/pipeline.hpp"
#include "perception/plane_geometry.hpp"
#include "perception/reconstruction.hpp"
#include "perception/region_growing.hpp"
#include "synthetic.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace stairs {
namespace {

Level level(float z, float s_min, float s_max) { return {-1, z, s_min, s_max, -0.5f, 0.5f}; }

// A plane known only by its kind and stair-aligned extent.
void add_plane(PlaneSet& ps, PlaneKind kind, const PlaneExtent& e) {
  Plane p;
  p.kind = kind;
  ps.planes.push_back(p);
  ps.extents.push_back(e);
}

// Three levels 0.18 m apart, 1 m wide, the lowest from `near_s` to the first
// riser at `riser_s`, the others 0.25 m deep, and the two risers between them
// (planes 0-2 the levels, 3-4 the risers).
PlaneSet three_levels(float near_s, float riser_s, float low_z) {
  PlaneSet ps;
  for (int k = 0; k < 3; ++k) {
    const float z = low_z + 0.18f * k, s0 = k == 0 ? near_s : riser_s + 0.25f * (k - 1), s1 = riser_s + 0.25f * k;
    add_plane(ps, PlaneKind::Tread, {s0, s1, -0.5f, 0.5f, z, z, 0.5f * (s0 + s1), z});
  }
  for (int k = 0; k < 2; ++k) {
    const float s = riser_s + 0.25f * k, z0 = low_z + 0.18f * k;
    add_plane(ps, PlaneKind::Riser, {s, s, -0.5f, 0.5f, z0, z0 + 0.18f, s, z0 + 0.09f});
  }
  return ps;
}

TEST(PerceptionGrammar, DinBoundsWithTolerance) {
  const StairConfig c;
  EXPECT_TRUE(din_riser_ok(0.17, c));
  EXPECT_TRUE(din_riser_ok(0.09, c));   // 0.14 - 40 %
  EXPECT_FALSE(din_riser_ok(0.07, c));
  EXPECT_FALSE(din_riser_ok(0.30, c));  // 0.20 + 40 % = 0.28
  EXPECT_TRUE(din_tread_ok(0.28, c));
  EXPECT_FALSE(din_tread_ok(0.10, c));
  EXPECT_TRUE(din_rule_ok(0.17, 0.28, c));
  EXPECT_FALSE(din_rule_ok(0.05, 0.2, c));
}

TEST(PerceptionGrammar, AscendingChainFromTheFloor) {
  const std::vector<Level> levels = {level(-1.0f, 0.5f, 1.5f), level(-0.83f, 1.5f, 1.78f), level(-0.66f, 1.78f, 2.06f),
                                     level(-0.49f, 2.06f, 2.2f)};
  const StairChain ch = best_chain(levels, StairConfig{});
  EXPECT_EQ(ch.direction, Direction::Up);
  EXPECT_EQ(ch.steps(), 3);
}

// A ramp cut into patches: each patch's heights reach most of the way to the
// next, so no patch is a level a step rises from (the same heights as flat
// levels make a flight).
TEST(PerceptionGrammar, LevelsThatRiseThroughTheRiseAreNoSteps) {
  std::vector<Level> levels = {level(-1.0f, 0.5f, 1.5f), level(-0.83f, 1.5f, 1.78f), level(-0.66f, 1.78f, 2.06f),
                               level(-0.49f, 2.06f, 2.2f)};
  for (Level& l : levels) l.reach_above_m = l.reach_below_m = 0.06f;  // within noise of a 0.17 m rise
  EXPECT_EQ(best_chain(levels, StairConfig{}).steps(), 3);
  for (Level& l : levels) l.reach_above_m = l.reach_below_m = 0.1f;  // a slope: more than half the rise
  EXPECT_EQ(best_chain(levels, StairConfig{}).steps(), 0);
}

// A step lower than DIN's lowest rise (a real Kinect v2 flight's 8 cm first riser) is no step the
// grammar takes; the floor, the level after it and the one after that then look like a flight whose
// first "step" rises 18 cm over a 28 cm gap, the low step's tread filling that gap. A tread plane
// seen between two, in height and along the stair, says they are no consecutive steps.
TEST(PerceptionGrammar, NoStepOverALevelBetween) {
  std::vector<Level> levels = {level(-1.0f, 0.0f, 0.5f), level(-0.92f, 0.52f, 0.76f), level(-0.82f, 0.78f, 1.06f),
                               level(-0.64f, 1.08f, 1.36f)};
  for (size_t i = 0; i < levels.size(); ++i) levels[i].plane = static_cast<int>(i);  // tread planes, all seen
  const StairChain ch = best_chain(levels, StairConfig{});
  ASSERT_EQ(ch.direction, Direction::Up);
  ASSERT_EQ(ch.steps(), 2);
  EXPECT_FLOAT_EQ(ch.levels.front().z, -0.92f) << "from the low step's tread, not over it from the floor";
}

TEST(PerceptionGrammar, DescendingChainFromTheLanding) {
  // Going down each lower tread is seen beyond the nosing above it.
  const std::vector<Level> levels = {level(-1.0f, 0.5f, 1.5f), level(-1.17f, 1.6f, 1.78f), level(-1.34f, 1.9f, 2.06f),
                                     level(-1.51f, 2.2f, 3.5f)};
  const StairChain ch = best_chain(levels, StairConfig{});
  EXPECT_EQ(ch.direction, Direction::Down);
  EXPECT_EQ(ch.steps(), 3);
  PlaneSet ps;
  std::vector<Step> steps = steps_from_chain(ps, ch, StairConfig{});
  ASSERT_EQ(steps.size(), 3u);
  reconstruct(ps, ch, steps, StairConfig{});
  // Occluded tread depths come from nosing to nosing; risers are rebuilt.
  EXPECT_NEAR(*steps[1].tread_depth_m, 0.28, 1e-5);
  EXPECT_NEAR(*steps[2].tread_depth_m, 0.28, 1e-5);
  EXPECT_EQ(ps.planes.size(), 3u);
  for (const Step& s : steps) {
    ASSERT_GE(s.riser_plane, 0);
    EXPECT_EQ(ps.planes[s.riser_plane].source, PlaneSource::Reconstructed);
    EXPECT_NEAR(*s.riser_height_m, 0.17, 1e-5);
  }
}

// Going down from the landing, a small level far beyond the flight a few centimetres below the
// landing (the top of a person's head at the bottom of the stair, 4 m ahead) is a valid "landing"
// after it, and the nearest in height: taken as its successor it left the landing out of the chain,
// and the model never had the flight's first edge. The step a tread's depth on comes first.
TEST(PerceptionGrammar, AFarLevelJustBelowTheLandingDoesNotCutTheDescentFromIt) {
  const Level head = level(-1.10f, 3.87f, 4.10f);
  const std::vector<Level> levels = {level(-1.0f, 0.5f, 1.5f), head, level(-1.17f, 1.6f, 1.78f),
                                     level(-1.34f, 1.9f, 2.06f), level(-1.51f, 2.2f, 3.5f)};
  const StairChain ch = best_chain(levels, StairConfig{});
  EXPECT_EQ(ch.direction, Direction::Down);
  ASSERT_EQ(ch.steps(), 3);
  EXPECT_FLOAT_EQ(ch.levels.front().z, -1.0f);
  for (const Level& l : ch.levels) EXPECT_NE(l.z, head.z);
}

// Going down, a level seen only as a nosing's jump is a tread between two
// nosings; a jump 4 m past the last nosing (noise at the sensor's range on
// the floor below) is no 4 m landing: the floor's plane is the next level.
TEST(PerceptionGrammar, AJumpAloneIsNoLandingGoingDown) {
  Level far_jump = level(-1.49f, 5.5f, 5.5f);
  far_jump.far_edge = true;
  far_jump.edge_s = 5.5f;
  const std::vector<Level> levels = {level(-1.0f, 0.5f, 1.5f), level(-1.17f, 1.6f, 1.78f), level(-1.34f, 1.9f, 2.06f),
                                     level(-1.51f, 2.2f, 4.9f), far_jump};
  const StairChain ch = best_chain(levels, StairConfig{});
  EXPECT_EQ(ch.direction, Direction::Down);
  ASSERT_EQ(ch.steps(), 3);
  EXPECT_EQ(ch.levels.back().z, -1.51f);
  EXPECT_EQ(ch.landings, 0);
}

// A descending flight is seen from above. A robot's camera 0.45 m up saw, from below, the depth
// jumps of a chair's back (0.43 m above the eye), a table's edge (0.24 m) and the chair's seat (at
// the eye): three levels falling away from the camera, taken as a flight going down (a kitchen table,
// a Kinect v2 robot: 3 false steps in the model). The same levels below the eye are a descent.
TEST(PerceptionGrammar, LevelsAboveTheEyeAreNoDescent) {
  const auto edge = [](float z, float s) {
    Level l = level(z, s, s);
    l.far_edge = true;
    l.edge_s = s;
    return l;
  };
  const StairConfig c;
  EXPECT_EQ(best_chain({edge(0.43f, 2.72f), edge(0.24f, 3.04f), edge(-0.02f, 3.32f)}, c).steps(), 0);
  const StairChain below = best_chain({edge(-0.43f, 2.72f), edge(-0.62f, 3.04f), edge(-0.88f, 3.32f)}, c);
  EXPECT_EQ(below.direction, Direction::Down);
  EXPECT_EQ(below.steps(), 2);
}

TEST(PerceptionReconstruction, AMidLandingEndingInADropIsTheLastStepGoingDown) {
  // The same flight seen from above, but its last level ends in a depth jump
  // 1.3 m on: a landing with the next flight below its edge, not the floor.
  // The jump lies 2 cm beyond the plane's trimmed extent: the nosing is the jump.
  std::vector<Level> levels = {level(-1.0f, 0.5f, 1.5f), level(-1.17f, 1.6f, 1.78f), level(-1.34f, 1.9f, 2.06f),
                               level(-1.51f, 2.2f, 3.5f)};
  levels.back().far_edge = true;
  levels.back().edge_s = 3.52f;
  const StairConfig cfg;
  const StairChain ch = best_chain(levels, cfg);
  ASSERT_EQ(ch.steps(), 3);
  PlaneSet ps;
  std::vector<Step> steps = steps_from_chain(ps, ch, StairConfig{});
  reconstruct(ps, ch, steps, cfg);
  ASSERT_EQ(steps.size(), 4u);
  EXPECT_TRUE(steps[3].landing);
  EXPECT_NEAR(steps[3].nosing_m.x(), 3.52, 1e-5);
  EXPECT_NEAR(steps[3].nosing_m.z(), -1.51, 1e-5);
  EXPECT_NEAR(*steps[3].tread_depth_m, 3.52 - 2.06, 1e-5);
  EXPECT_NEAR(*steps[3].riser_height_m, 0.17, 1e-5);  // the chain's median: its riser is out of view
}

TEST(PerceptionGrammar, NoChainOnImplausibleLevels) {
  const StairConfig c;
  // A table top 0.75 m above the floor.
  EXPECT_EQ(best_chain({level(-1.0f, 0.5f, 3.0f), level(-0.25f, 1.5f, 2.3f)}, c).steps(), 0);
  // Levels 3 cm apart: no riser.
  EXPECT_EQ(best_chain({level(-1.0f, 0.5f, 1.5f), level(-0.97f, 1.5f, 1.8f)}, c).steps(), 0);
}

// A mounted camera on a level carrier: the level at the mount's height is its
// ground; a level a riser off, or a tilted carrier, is not (issue 15, the mount).
TEST(PerceptionCameraHeight, AMountNamesTheGroundOnlyAtItsHeightAndTilt) {
  const DepthImage frame = test::render_stairs(640, 480, -35, 0, 1.0, 4, 1.3);
  const auto height = [&](float mount_m, float pitch_deg) {
    PerceptionConfig cfg;
    cfg.mount.height_m = mount_m;
    cfg.mount.pitch_deg = pitch_deg;
    return Pipeline(cfg).process(frame).camera.height_m;
  };
  ASSERT_TRUE(height(1.0f, -35.0f).has_value());
  EXPECT_NEAR(*height(1.0f, -35.0f), 1.0, 0.01);
  EXPECT_FALSE(height(1.17f, -35.0f).has_value()) << "a riser below the level seen";
  EXPECT_FALSE(height(1.0f, -20.0f).has_value()) << "the carrier tilted 15 deg";
  EXPECT_FALSE(height(0.0f, -35.0f).has_value()) << "no mount";
}

// Looking steeply down, the point straight beneath is in view: the height is the level of the cells
// nearest the plumb line, where cells surround it and the nearest agree (issue 15). Over a floor it
// is known, with a step's riser 3 cm ahead too; with the plumb line at the image's edge the cells do
// not surround it: unknown.
TEST(PerceptionCameraHeight, StraightBeneathIsTheLevelOfTheCellsNearestThePlumbLine) {
  const auto height = [](double pitch_deg, double first_riser_m) {
    return Pipeline().process(test::render_stairs(640, 480, pitch_deg, 0, 0.8, 2, first_riser_m)).camera.height_m;
  };
  ASSERT_TRUE(height(-75, 1.0).has_value()) << "over the floor";
  EXPECT_NEAR(*height(-75, 1.0), 0.8, 0.01);
  ASSERT_TRUE(height(-75, 0.03).has_value()) << "a riser 3 cm ahead";
  EXPECT_NEAR(*height(-75, 0.03), 0.8, 0.01) << "the floor, not the step ahead";
  // 90.2 deg below the horizon at the lowest row: beneath is in view, but nothing behind it.
  EXPECT_FALSE(height(-65.6, 1.0).has_value()) << "the plumb line at the image's lowest row";
}

TEST(PerceptionSteps, SyntheticAscendingStairsEndToEnd) {
  Pipeline p;
  const Observation o = p.process(test::render_stairs(640, 480, -35, 0, 1.0, 4, 1.3));
  ASSERT_TRUE(o.camera.valid);
  EXPECT_EQ(o.direction, Direction::Up);
  ASSERT_GE(o.steps.size(), 3u);
  for (size_t k = 0; k < o.steps.size(); ++k) {
    EXPECT_NEAR(*o.steps[k].riser_height_m, 0.17, 0.02);
    // Nosing k at x = 1.3 + k * 0.28, z = -1 + (k + 1) * 0.17.
    EXPECT_NEAR(o.steps[k].nosing_m.x(), 1.3 + k * 0.28, 0.04);
    EXPECT_NEAR(o.steps[k].nosing_m.z(), -1.0 + (k + 1) * 0.17, 0.03);
    if (k + 1 < o.steps.size()) {
      EXPECT_NEAR(*o.steps[k].tread_depth_m, 0.28, 0.03);
    }
  }
  // The floor fills the image's lowest row, but one frame cannot tell it from a
  // landing with steps hidden below the view: no height (issue 15).
  EXPECT_FALSE(o.camera.height_m.has_value());
  ASSERT_TRUE(o.camera.distance_m.has_value());
  EXPECT_NEAR(*o.camera.distance_m, 1.3, 0.04);
  // Tread/riser samples are capped and in the gravity frame.
  int treads = 0;
  for (const Plane& pl : o.planes) {
    EXPECT_LE(pl.points.size(), 1024u);
    if (pl.kind == PlaneKind::Tread) {
      ++treads;
      for (const auto& q : pl.points) EXPECT_NEAR(q.z(), pl.centroid.z(), 0.03);
    }
  }
  EXPECT_GE(treads, 4);
  // The normal-image edges are a diagnostic, off by default: no stage of theirs.
  const std::vector<std::string> names = {"normals",           "region_growing", "concave_corners",
                                          "bridged_surfaces",  "gravity",        "plane_geometry",
                                          "edges_depth_jumps", "steps",          "grammar",
                                          "reconstruction",    "verification"};
  ASSERT_EQ(o.stages.size(), names.size());
  for (size_t i = 0; i < names.size(); ++i) EXPECT_EQ(o.stages[i].name, names[i]);
}

// Near the flight the first riser's foot is below the view and the lowest level in view is the
// first tread: that step is completed from its riser (reconstruction). Its nosing lies at the
// riser's face, as every other step's: from its tread's trimmed front it lay a centimetre or more
// behind, its tread came out short and the steps beside it disagreed (issue 14).
TEST(PerceptionReconstruction, TheNearestStepsNosingIsItsRisersFace) {
  constexpr double kFirstRiser = 0.6, kTread = 0.28;
  Pipeline p;
  const Observation o = p.process(test::render_stairs(640, 480, -35, 0, 1.0, 4, kFirstRiser, 0.17, kTread));
  ASSERT_EQ(o.direction, Direction::Up) << o.status;
  ASSERT_GE(o.steps.size(), 3u);
  for (size_t k = 0; k < o.steps.size(); ++k) {
    EXPECT_NEAR(o.steps[k].nosing_m.x(), kFirstRiser + k * kTread, 0.005) << "step " << k;
    if (k + 1 < o.steps.size()) {
      EXPECT_NEAR(*o.steps[k].tread_depth_m, kTread, 0.005) << "step " << k;
    }
  }
}

TEST(PerceptionSteps, ANosingsSlabIsNoRiser) {
  // Looking down an ascending flight with 3 cm nosing overhangs: each riser's
  // face is seen below its slab, and the slab's own front face, 3.5 cm tall at
  // the tread's level and 3 cm nearer, is a plane of its own. The riser stands
  // on the level below; taking the slab put nosings 3 cm apart from the faces
  // and treads 0.20-0.25 m for 0.222.
  constexpr float kRise = 0.15f, kTread = 0.222f, kOverhang = 0.03f, kFloor = -0.8f, kFirstFace = 0.6f;
  PlaneSet ps;
  add_plane(ps, PlaneKind::Tread, {0.1f, kFirstFace, -0.5f, 0.5f, kFloor, kFloor, 0.35f, kFloor});
  for (int k = 0; k < 3; ++k) {
    const float face = kFirstFace + kTread * k, below = kFloor + kRise * k, top = below + kRise;
    add_plane(ps, PlaneKind::Tread, {face - kOverhang + 0.01f, face + kTread - 0.01f, -0.5f, 0.5f, top, top,
                                     face + 0.5f * kTread, top});
    add_plane(ps, PlaneKind::Riser, {face, face, -0.5f, 0.5f, below + 0.01f, top - 0.06f, face, below + 0.05f});
    if (k != 1) {  // a slab seen as its own plane on some steps only
      const float slab = face - kOverhang;
      add_plane(ps, PlaneKind::Riser, {slab, slab, -0.5f, 0.5f, top - 0.035f, top - 0.005f, slab, top - 0.02f});
    }
  }
  const StairConfig cfg;
  const StairChain chain = best_chain(tread_levels(ps, {}, cfg), cfg);
  ASSERT_EQ(chain.direction, Direction::Up);
  const std::vector<Step> steps = steps_from_chain(ps, chain, cfg);
  ASSERT_EQ(steps.size(), 3u);
  for (size_t k = 0; k < steps.size(); ++k) {
    EXPECT_NEAR(ps.axial(steps[k].nosing_m), kFirstFace + kTread * k, 1e-4) << "step " << k;
    if (k + 1 < steps.size()) {
      EXPECT_NEAR(ps.axial(steps[k + 1].nosing_m) - ps.axial(steps[k].nosing_m), kTread, 1e-4) << "step " << k;
    }
  }
}

// An open-sided flight in a room wider than it: the floor beside the flight (to its left, t > 0.5)
// runs on past the first riser, under the flight it ends at the riser's foot. The floor's box
// reached 0.7 m past the first riser, more than a level's gap, and the first step was lost in every
// frame that showed that floor (a hand-held Kinect v2 ascent: step 0 missing in 24 frames of 88).
// Where the floor runs on under the level above too (seen beneath a seat), it is no step's floor.
TEST(PerceptionSteps, TheFloorBesideAnOpenSidedFlightEndsAtItsFirstRiserUnderIt) {
  const StairConfig cfg;
  for (const bool under_too : {false, true}) {
    PlaneSet ps = three_levels(0.3f, 1.0f, -1.0f);  // the floor to the first riser at 1.0, two treads
    PlaneExtent& floor = ps.extents[0];
    floor.s_max = 1.7f;
    floor.t_max = 2.0f;
    floor.strips.t0 = -0.5f;
    floor.strips.width = 0.1f;
    for (int k = 0; k < 25; ++k) {
      floor.strips.s_min.push_back(0.3f);
      floor.strips.s_max.push_back(k >= 10 || under_too ? 1.7f : 1.0f);
    }
    const StairChain chain = best_chain(tread_levels(ps, {}, cfg), cfg);
    if (under_too) {
      EXPECT_EQ(chain.steps(), 1) << "a floor seen on beneath the level above is no step's floor";
      continue;
    }
    ASSERT_EQ(chain.direction, Direction::Up);
    ASSERT_EQ(chain.steps(), 2) << "the first step, from the floor";
    const std::vector<Step> steps = steps_from_chain(ps, chain, cfg);
    ASSERT_EQ(steps.size(), 2u);
    EXPECT_NEAR(ps.axial(steps[0].nosing_m), 1.0f, 1e-4);
    EXPECT_NEAR(*steps[0].riser_height_m, 0.18f, 1e-4);
  }
}

// A floor at -0.45 m to 1 m ahead and the three risers of a flight (rise 0.18 m,
// going 0.25 m) without their treads: planes 0-3.
PlaneSet risers_on_a_floor() {
  PlaneSet ps;
  add_plane(ps, PlaneKind::Tread, {0.3f, 1.0f, -0.5f, 0.5f, -0.45f, -0.45f, 0.65f, -0.45f});
  for (int k = 0; k < 3; ++k) {
    const float s = 1.0f + 0.25f * k, z0 = -0.45f + 0.18f * k;
    add_plane(ps, PlaneKind::Riser, {s, s, -0.5f, 0.5f, z0, z0 + 0.18f, s, z0 + 0.09f});
  }
  return ps;
}

// Far up a flight each level loses its cells at both corners of a step (a
// D435 at 2.5 m: the tread above started 5-9 cm behind the riser's face). The
// face lies between where the level below stops and where the tread above
// starts: it is searched for there, and without a segmented riser the band's
// middle is the nosing, not the tread's trimmed front.
TEST(PerceptionSteps, ARisersFaceLiesBetweenTheLevelBelowAndTheTreadAbove) {
  constexpr float kFace = 1.25f, kTread = 0.25f;
  const StairConfig cfg;
  PlaneSet ps = three_levels(0.3f, 1.0f, -1.0f);  // faces at 1.0 and 1.25
  ps.extents[1].s_max = kFace - 0.05f;             // the level below stops 5 cm short
  ps.extents[2].s_min = kFace + 0.08f;             // the tread above starts 8 cm behind
  ASSERT_LT(0.08f, cfg.riser_at_nosing_m);
  const auto second_nosing = [&] {
    const StairChain chain = best_chain(tread_levels(ps, {}, cfg), cfg);
    EXPECT_EQ(chain.direction, Direction::Up);
    const std::vector<Step> steps = steps_from_chain(ps, chain, cfg);
    EXPECT_EQ(steps.size(), 2u);
    return steps.size() == 2 ? ps.axial(steps[1].nosing_m) - ps.axial(steps[0].nosing_m) : 0.0f;
  };
  EXPECT_NEAR(second_nosing(), kTread, 1e-4) << "the segmented face within riser_at_nosing_m";
  // The tread above starts farther behind than riser_at_nosing_m: the face is still in the band.
  ps.extents[2].s_min = kFace + 1.2f * cfg.riser_at_nosing_m;
  EXPECT_NEAR(second_nosing(), kTread, 1e-4) << "the segmented face in the band";
  // No riser segmented there: the band's middle, 1.5 cm off for unequal losses (the tread's front: 8 cm).
  ps.extents[2].s_min = kFace + 0.08f;
  ps.planes[4].kind = PlaneKind::Other;
  EXPECT_NEAR(second_nosing(), kTread + 0.015f, 1e-4);
  // A floor wider than the flight runs on beside it: no band, the tread's front.
  ps.extents[1].s_max = kFace + 0.3f;
  EXPECT_NEAR(second_nosing(), kTread + 0.08f, 1e-4);
}

// Looking steeply down an ascent with 3 cm nosing overhangs, each slab hides
// the level below up to its front: both levels end at the slab's front, and a
// face no riser shows lies an overhang behind that band. It stands where the
// faces that are shown stand from their bands: the slab's front on some steps
// and the faces on others made a Kinect v2's treads 26-30 cm for 28.
TEST(PerceptionSteps, AnUnseenFaceStandsWhereTheSeenOnesStandFromTheirBands) {
  constexpr float kRise = 0.17f, kTread = 0.28f, kOverhang = 0.03f, kFloor = -0.8f, kFirstFace = 0.6f;
  const StairConfig cfg;
  PlaneSet ps;
  add_plane(ps, PlaneKind::Tread, {0.1f, kFirstFace - kOverhang, -0.5f, 0.5f, kFloor, kFloor, 0.35f, kFloor});
  for (int k = 0; k < 3; ++k) {
    const float face = kFirstFace + kTread * k, below = kFloor + kRise * k, top = below + kRise;
    // The tread from its slab's front (1 cm of cells lost) to where the next slab hides it.
    add_plane(ps, PlaneKind::Tread, {face - kOverhang + 0.01f, face + kTread - kOverhang, -0.5f, 0.5f, top, top,
                                     face + 0.5f * kTread, top});
    if (k != 1)  // the second riser's face is not segmented
      add_plane(ps, PlaneKind::Riser, {face, face, -0.5f, 0.5f, below + 0.01f, top - 0.06f, face, below + 0.05f});
  }
  const StairChain chain = best_chain(tread_levels(ps, {}, cfg), cfg);
  ASSERT_EQ(chain.direction, Direction::Up);
  const std::vector<Step> steps = steps_from_chain(ps, chain, cfg);
  ASSERT_EQ(steps.size(), 3u);
  for (size_t k = 0; k < steps.size(); ++k)
    EXPECT_NEAR(ps.axial(steps[k].nosing_m), kFirstFace + kTread * k, 0.006) << "step " << k;
}

// A level seen only as its nosing's depth jump (the top tread, at a grazing angle) starts at the
// nosing itself: it lost no cells at the corner, and its "band" with the tread below put that face
// half a band off its middle. Carried to a face no riser shows (the second), that offset made a
// Kinect v2's treads 18 and 27 cm for 24. The faces the seen treads' bands show are at the middle.
TEST(PerceptionSteps, ANosingsJumpIsNoTreadThatLostItsFrontToACorner) {
  constexpr float kRise = 0.15f, kTread = 0.24f, kFloor = -1.2f, kFirstFace = 3.0f, kLost = 0.04f;
  const StairConfig cfg;
  PlaneSet ps;
  add_plane(ps, PlaneKind::Tread, {2.0f, kFirstFace - kLost, -0.5f, 0.5f, kFloor, kFloor, 2.5f, kFloor});
  for (int k = 0; k < 2; ++k) {  // two treads, each short of both its faces
    const float face = kFirstFace + kTread * k, top = kFloor + kRise * (k + 1);
    add_plane(ps, PlaneKind::Tread, {face + kLost, face + kTread - kLost, -0.5f, 0.5f, top, top,
                                     face + 0.5f * kTread, top});
  }
  for (int k : {0, 2}) {  // the second riser's face is not segmented
    const float face = kFirstFace + kTread * k, below = kFloor + kRise * k;
    add_plane(ps, PlaneKind::Riser, {face, face, -0.5f, 0.5f, below, below + kRise, face, below + 0.5f * kRise});
  }
  ps.extents.back().top_in_view = false;  // the third riser's top: its nosing's jump shows the level
  JumpEdge nosing;  // the third tread, seen only as its nosing's jump
  nosing.s = nosing.nosing_s = kFirstFace + 2 * kTread;
  nosing.z = kFloor + 3 * kRise;
  nosing.t_min = -0.5f;
  nosing.t_max = 0.5f;
  const StairChain chain = best_chain(tread_levels(ps, {nosing}, cfg), cfg);
  ASSERT_EQ(chain.direction, Direction::Up);
  const std::vector<Step> steps = steps_from_chain(ps, chain, cfg);
  ASSERT_EQ(steps.size(), 3u);
  for (size_t k = 0; k < steps.size(); ++k)
    EXPECT_NEAR(ps.axial(steps[k].nosing_m), kFirstFace + kTread * k, 1e-4) << "step " << k;
}

TEST(PerceptionSteps, ARiserCutByMissingDepthIsNoFootInView) {
  // A robot's time-of-flight camera reads nothing nearer than 0.5 m: the lower
  // part of the first riser and the floor before it are missing, though not at
  // the image's border. The riser is cut there, not ended: its rise is the
  // chain's, flagged, never its seen part measured as a short first step.
  constexpr double kHeight = 0.45, kRise = 0.17, kCut = 0.07;
  DepthImage img = test::render_stairs(640, 480, -10, 0, kHeight, 4, 0.8, kRise, 0.28);
  const Eigen::Matrix3d R = test::optical_to_world(-10, 0);
  for (int v = 0; v < img.K.height; ++v)
    for (int u = 0; u < img.K.width; ++u) {
      uint16_t& d = img.depth[static_cast<size_t>(v) * img.K.width + u];
      const Eigen::Vector3d p = R * Eigen::Vector3d((u - img.K.cx) / img.K.fx, (v - img.K.cy) / img.K.fy, 1.0) * (d * 1e-3);
      if (d && p.z() < -kHeight + kCut) d = 0;
    }
  Pipeline p;
  const Observation o = p.process(img);
  ASSERT_EQ(o.direction, Direction::Up) << o.status;
  ASSERT_GE(o.steps.size(), 2u);
  const Step& first = o.steps.front();
  ASSERT_TRUE(first.riser_height_m.has_value());
  EXPECT_NEAR(first.nosing_m.z(), -kHeight + kRise, 0.01);
  if (!(first.inferred & kStepRiserInferred)) {
    EXPECT_NEAR(*first.riser_height_m, kRise, 0.01);
  }
}

TEST(PerceptionSteps, SingleCurbIsNoStaircase) {
  Pipeline p;
  const Observation o = p.process(test::render_stairs(640, 480, -35, 0, 1.0, 1, 1.3, 0.15, 5.0));
  EXPECT_TRUE(o.camera.valid);
  EXPECT_EQ(o.direction, Direction::None);
  EXPECT_TRUE(o.steps.empty());
}

// Seen steeply from above (a D435 hand-held at 0.6 m), a riser ends 8.5 cm below its tread: the
// nosing's slab and the hole at its edge hide the rest. A tread whose front edge stands at the
// riser's face is that riser's own, whatever of the riser lies hidden below it (up to a rise): the
// riser's visible top is no level (it made an 8.5 cm and a 25.5 cm step of two 17 cm ones). The top
// of a riser whose tread starts a run behind it (the next step's) stays a level.
TEST(PerceptionSteps, ARisersTopHiddenUnderItsTreadsNosingIsNoLevel) {
  PlaneSet ps;
  add_plane(ps, PlaneKind::Tread, {0.30f, 0.58f, -0.7f, 0.4f, -0.845f, -0.845f, 0.44f, -0.845f});
  add_plane(ps, PlaneKind::Riser, {0.60f, 0.60f, -0.7f, 0.4f, -0.845f, -0.760f, 0.60f, -0.80f});
  add_plane(ps, PlaneKind::Tread, {0.59f, 0.85f, -0.7f, 0.4f, -0.675f, -0.675f, 0.72f, -0.675f});
  add_plane(ps, PlaneKind::Riser, {0.88f, 0.88f, -0.7f, 0.4f, -0.675f, -0.505f, 0.88f, -0.59f});
  add_plane(ps, PlaneKind::Tread, {0.88f, 1.12f, -0.7f, 0.4f, -0.505f, -0.505f, 1.0f, -0.505f});
  const StairConfig cfg;
  std::vector<float> z;
  for (const Level& l : tread_levels(ps, {}, cfg)) z.push_back(l.z);
  EXPECT_EQ(z, (std::vector<float>{-0.845f, -0.675f, -0.505f}));
  const StairChain chain = best_chain(tread_levels(ps, {}, cfg), cfg);
  ASSERT_EQ(chain.levels.size(), 3u);
  EXPECT_NEAR(chain.levels[1].z - chain.levels[0].z, 0.17f, 1e-5);
  // The middle tread unseen: the lower riser's top is the next level (its own tread's front).
  PlaneSet edge_on = ps;
  edge_on.extents[2].t_max = edge_on.extents[2].t_min + 0.5f * cfg.min_step_width_m;  // too narrow for a level
  z.clear();
  for (const Level& l : tread_levels(edge_on, {}, cfg)) z.push_back(l.z);
  EXPECT_EQ(z, (std::vector<float>{-0.845f, -0.760f, -0.505f}));
}

// A face taller than the highest rise is no riser (a wall, a cabinet's front): its top is no tread's
// front. A D435 robot saw a room's back wall at 5 m in two fragments, their tops where its depth
// gave out (1.05 and 1.15 m tall), and their tops made a two-step flight. Faces one rise tall keep
// their tops as levels.
TEST(PerceptionSteps, ATopOfAFaceTallerThanARiseIsNoLevel) {
  PlaneSet ps;
  add_plane(ps, PlaneKind::Tread, {0.3f, 2.2f, -1.3f, 0.6f, -0.45f, -0.45f, 0.8f, -0.45f});
  add_plane(ps, PlaneKind::Riser, {4.79f, 4.79f, -3.2f, -1.8f, -0.39f, 0.66f, 4.79f, 0.05f});
  add_plane(ps, PlaneKind::Riser, {5.05f, 5.05f, -2.7f, 2.0f, -0.28f, 0.87f, 5.05f, 0.23f});
  const StairConfig cfg;
  std::vector<float> z;
  for (const Level& l : tread_levels(ps, {}, cfg)) z.push_back(l.z);
  EXPECT_EQ(z, (std::vector<float>{-0.45f}));
  // One rise tall, the same faces' tops are the treads' fronts.
  ps.extents[1].z_min = 0.66f - 0.17f;
  ps.extents[2].z_min = 0.87f - 0.17f;
  z.clear();
  for (const Level& l : tread_levels(ps, {}, cfg)) z.push_back(l.z);
  std::sort(z.begin(), z.end());
  EXPECT_EQ(z, (std::vector<float>{-0.45f, 0.66f, 0.87f}));
}

// A robot's camera below 3 cm nosings: a riser's upper part, merged with its nosing's slab, is
// fitted tilted (no riser's plane) and reaches up to the image's top; its lower part is a riser of its
// own, 4.5 cm tall. That part's top is no nosing: the face goes on above it (a 9 cm "rise" and a false
// step before; a Kinect v2 robot's ascent, 3 false frames). Without the upper part in view, the lower
// part's top stands for a level as before.
TEST(PerceptionSteps, ARisersTopIsNoLevelWhereItsFaceGoesOnAbove) {
  PlaneSet ps;
  const Eigen::Vector3f facing(-1.0f, 0.0f, 0.0f);
  auto add = [&](PlaneKind kind, const PlaneExtent& e, const Eigen::Vector3f& n) {
    add_plane(ps, kind, e);
    ps.planes.back().normal = n;
  };
  add(PlaneKind::Tread, {0.3f, 1.0f, -0.5f, 0.5f, -0.45f, -0.45f, 0.65f, -0.45f}, Eigen::Vector3f::UnitZ());
  for (int k = 0; k < 2; ++k) {
    const float s = 1.0f + 0.25f * k, z0 = -0.45f + 0.18f * k;
    add(PlaneKind::Riser, {s, s, -0.5f, 0.5f, z0, z0 + 0.18f, s, z0 + 0.09f}, facing);
  }
  add(PlaneKind::Riser, {1.5f, 1.5f, -0.3f, 0.2f, -0.09f, -0.045f, 1.5f, -0.07f}, facing);  // the lower part
  const StairConfig cfg;
  const auto tops = [&] {
    std::vector<float> z;
    for (const Level& l : tread_levels(ps, {}, cfg)) z.push_back(l.z);
    return z;
  };
  const std::vector<float> lower_part_alone = tops();
  ASSERT_EQ(lower_part_alone.size(), 4u);
  EXPECT_NEAR(lower_part_alone[3], -0.045f, 1e-5);
  PlaneExtent upper{1.47f, 1.51f, -0.5f, 0.5f, -0.09f, 0.04f, 1.49f, -0.02f};
  upper.top_in_view = false;
  add(PlaneKind::Other, upper, Eigen::Vector3f(-0.94f, 0.0f, -0.34f).normalized());
  const std::vector<float> with_upper = tops();
  ASSERT_EQ(with_upper.size(), 3u);
  EXPECT_NEAR(with_upper[2], -0.09f, 1e-5);
  // The cells between the two segments are often neither's: the upper part starting 2 cm above the
  // lower part's top (within a level's tolerance) goes on from it all the same.
  ps.extents.back().z_min = -0.025f;
  EXPECT_EQ(tops().size(), 3u);
  // A face that starts a level above the riser's top is the next step's, not this one's.
  ps.extents.back().z_min = -0.045f + cfg.same_level_m + 0.01f;
  EXPECT_EQ(tops().size(), 4u);
  ps.extents.back().z_min = -0.09f;
  // A side wall beside the riser, reaching higher, is no face of it.
  ps.planes.back().normal = Eigen::Vector3f::UnitY();
  EXPECT_EQ(tops().size(), 4u);
}

TEST(PerceptionSteps, RisersWithoutTreadsGiveLevelsAtTheirTops) {
  // A camera level with the flight sees the floor and the risers, not the treads.
  PlaneSet ps = risers_on_a_floor();
  auto add = [&](PlaneKind kind, const PlaneExtent& e) { add_plane(ps, kind, e); };
  PlaneExtent cut{1.75f, 1.75f, -0.5f, 0.5f, 0.09f, 0.15f, 1.75f, 0.12f};
  cut.top_in_view = false;  // continues above the image: its top is no nosing
  add(PlaneKind::Riser, cut);
  add(PlaneKind::Riser, {0.6f, 0.6f, 0.2f, 0.26f, -0.45f, -0.27f, 0.6f, -0.36f});  // a chair leg
  const StairConfig cfg;
  const std::vector<Level> levels = tread_levels(ps, {}, cfg);
  ASSERT_EQ(levels.size(), 4u);
  for (int k = 1; k < 4; ++k) {
    EXPECT_EQ(levels[k].plane, -1);
    EXPECT_NEAR(levels[k].z, -0.45f + 0.18f * k, 1e-5);
    EXPECT_NEAR(levels[k].s_min, 1.0f + 0.25f * (k - 1), 1e-5);
  }
  const StairChain chain = best_chain(levels, cfg);
  EXPECT_EQ(chain.direction, Direction::Up);
  EXPECT_EQ(chain.steps(), 3);
  std::vector<Step> steps = steps_from_chain(ps, chain, cfg);
  ASSERT_EQ(steps.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(steps[k].riser_plane, k + 1);
    EXPECT_NEAR(steps[k].nosing_m.x(), 1.0 + 0.25 * k, 1e-4);
    EXPECT_NEAR(*steps[k].riser_height_m, 0.18, 1e-4);
  }
  // The cut riser stands a tread beyond the last riser's top, on its unseen
  // tread: the next step, its nosing a median rise above that level.
  reconstruct(ps, chain, steps, cfg);
  ASSERT_EQ(steps.size(), 4u);
  EXPECT_EQ(steps[3].riser_plane, 4);
  EXPECT_NEAR(steps[3].nosing_m.x(), 1.75, 1e-4);
  EXPECT_NEAR(steps[3].nosing_m.z(), 0.09 + 0.18, 1e-4);
  EXPECT_NEAR(*steps[2].tread_depth_m, 0.25, 1e-4);
}

// Under a nosing overhang the recessed riser meets the slab's front a slab's
// thickness below the tread, and cells across that edge face up: a horizontal
// band across the riser's face, 1 cm deep. A tread starts at its riser's top
// and runs back from it; the band is none, and the riser's top stays the level
// (a Kinect v2 robot's band 4 cm below the top stood for the tread: the
// model's rise came out 2.6 cm short).
TEST(PerceptionSteps, ABandAcrossARisersFaceIsNoTread) {
  PlaneSet ps = risers_on_a_floor();
  const float band_z = -0.45f + 0.18f * 2 - 0.04f;  // under the second riser's top
  add_plane(ps, PlaneKind::Tread, {1.245f, 1.255f, -0.5f, 0.5f, band_z, band_z, 1.25f, band_z});
  const StairConfig cfg;
  const std::vector<Level> levels = tread_levels(ps, {}, cfg);
  ASSERT_EQ(levels.size(), 4u);
  for (int k = 1; k < 4; ++k) EXPECT_NEAR(levels[k].z, -0.45f + 0.18f * k, 1e-5) << k;
  // A tread that runs back from the riser's top is one, even seen only 3 cm deep.
  ps.extents.back() = {1.25f, 1.28f, -0.5f, 0.5f, -0.09f, -0.09f, 1.265f, -0.09f};
  const std::vector<Level> with_tread = tread_levels(ps, {}, cfg);
  ASSERT_EQ(with_tread.size(), 4u);
  EXPECT_EQ(with_tread[2].plane, 4);
}

// A robot's camera below the treads sees only risers, up to a flight whose
// goings are 0.34 m (DIN allows 0.37): an unseen tread between two risers'
// tops is as deep as any plausible tread, not only as a gap between seen
// planes. A riser split across its width at range is one level, and the
// nosing's depth jump shows the step's width beyond the riser's fragments.
TEST(PerceptionSteps, RisersSeenFromBelowChainAcrossAnyPlausibleTread) {
  PlaneSet ps;
  auto add = [&](PlaneKind kind, const PlaneExtent& e) { add_plane(ps, kind, e); };
  add(PlaneKind::Tread, {0.3f, 1.0f, -0.5f, 0.5f, -0.45f, -0.45f, 0.65f, -0.45f});
  for (int k = 0; k < 3; ++k) {
    const float s = 1.0f + 0.34f * k, z0 = -0.45f + 0.16f * k;
    if (k < 2) {
      add(PlaneKind::Riser, {s, s, -0.5f, 0.5f, z0, z0 + 0.16f, s, z0 + 0.08f});
    } else {  // two fragments, 3 cm apart, whose tops agree within noise
      add(PlaneKind::Riser, {s, s, -0.4f, 0.0f, z0 + 0.05f, z0 + 0.16f, s, z0 + 0.1f});
      add(PlaneKind::Riser, {s + 0.01f, s + 0.01f, 0.03f, 0.2f, z0 + 0.06f, z0 + 0.165f, s + 0.01f, z0 + 0.11f});
    }
  }
  JumpEdge nosing;  // the third riser's top seen from below, across the flight
  nosing.s = nosing.nosing_s = 1.68f;
  nosing.z = -0.45f + 0.16f * 3;
  nosing.t_min = -0.5f;
  nosing.t_max = 0.5f;
  const StairConfig cfg;
  ASSERT_GT(0.34f, cfg.max_level_gap_m);  // more than a gap between two seen planes
  const std::vector<Level> levels = tread_levels(ps, {nosing}, cfg);
  ASSERT_EQ(levels.size(), 4u);
  EXPECT_TRUE(levels[3].far_edge);
  EXPECT_NEAR(levels[3].t_min, -0.5f, 1e-5);
  EXPECT_NEAR(levels[3].t_max, 0.5f, 1e-5);
  const StairChain chain = best_chain(levels, cfg);
  EXPECT_EQ(chain.direction, Direction::Up);
  ASSERT_EQ(chain.steps(), 3);
  std::vector<Step> steps = steps_from_chain(ps, chain, cfg);
  reconstruct(ps, chain, steps, cfg);
  ASSERT_EQ(steps.size(), 3u);
  EXPECT_NEAR(*steps[0].tread_depth_m, 0.34, 1e-4);
  EXPECT_NEAR(*steps[1].tread_depth_m, 0.34, 1e-4);
  EXPECT_NEAR(*steps[2].riser_height_m, 0.16, 0.006);
  EXPECT_NEAR(steps[2].width_m, 1.0, 1e-4);
  // A gap no tread has (0.6 m) is no step: a seen tread would be a landing, an unseen one is unknown.
  ps = PlaneSet{};
  add(PlaneKind::Tread, {0.3f, 1.0f, -0.5f, 0.5f, -0.45f, -0.45f, 0.65f, -0.45f});
  for (int k = 0; k < 2; ++k) {
    const float s = 1.0f + 0.6f * k, z0 = -0.45f + 0.16f * k;
    add(PlaneKind::Riser, {s, s, -0.5f, 0.5f, z0, z0 + 0.16f, s, z0 + 0.08f});
  }
  EXPECT_EQ(best_chain(tread_levels(ps, {}, cfg), cfg).steps(), 1);
}

// Rectangles rendered at 320x240 by a camera at the origin pitched `pitch_deg`, segmented and
// merged into planes by the default config.
struct Rect {
  Eigen::Vector3d c, n, u;  // centre, normal (towards the camera), horizontal in-plane axis; world
  double half_u, half_z;    // half-sizes along u and along v
  Eigen::Vector3d v = Eigen::Vector3d::UnitZ();  // the other in-plane axis (up for a vertical one)
};

PlaneSet planes_of(const std::vector<Rect>& rects, double pitch_deg, size_t min_segments) {
  DepthImage img;
  img.K = {320, 240, 262.5, 262.5, 159.5, 119.5};
  img.depth.assign(320 * 240, 0);
  const Eigen::Matrix3d R = test::optical_to_world(pitch_deg, 0);
  for (int v = 0; v < 240; ++v)
    for (int u = 0; u < 320; ++u) {
      const Eigen::Vector3d d = R * Eigen::Vector3d((u - 159.5) / 262.5, (v - 119.5) / 262.5, 1.0);
      double best = 1e9;
      for (const Rect& r : rects) {
        const double t = r.c.dot(r.n) / d.dot(r.n);  // along the optical ray, t = depth
        const Eigen::Vector3d q = t * d - r.c;
        if (t > 0 && t < best && std::abs(q.dot(r.u)) < r.half_u && std::abs(q.dot(r.v)) < r.half_z) best = t;
      }
      if (best < 1e9) img.depth[static_cast<size_t>(v) * 320 + u] = static_cast<uint16_t>(best * 1000);
    }
  const PerceptionConfig cfg;
  NormalGrid grid;
  compute_normals(img, cfg.normals, grid);
  std::vector<int> labels;
  const std::vector<Segment> segments = grow_regions(grid, cfg.region_growing, 320, 240, labels);
  EXPECT_GE(segments.size(), min_segments);
  return plane_geometry(grid, segments, R.cast<float>(), cfg.plane_geometry, cfg.output);
}

// A tread's extent along the stair is also taken in lateral strips, from all its cells: the floor
// before a flight 1 m wide runs on beside it, and under it ends at the first riser's foot.
TEST(PerceptionPlaneGeometry, TheFloorsStripsEndAtTheFirstRiserUnderTheFlight) {
  constexpr float kFirstRiser = 1.5f;
  const PerceptionConfig cfg;
  const DepthImage img = test::render_stairs(640, 480, -30, 0, 1.4, 5, kFirstRiser, 0.17, 0.28, 0.5);
  NormalGrid grid;
  compute_normals(img, cfg.normals, grid);
  std::vector<int> labels;
  const std::vector<Segment> segments = grow_regions(grid, cfg.region_growing, 640, 480, labels);
  const PlaneSet ps =
      plane_geometry(grid, segments, test::optical_to_world(-30, 0).cast<float>(), cfg.plane_geometry, cfg.output);
  ASSERT_NEAR(ps.yaw_rad, 0.0f, 0.01f);
  const PlaneExtent* floor = nullptr;
  for (size_t i = 0; i < ps.planes.size(); ++i)
    if (ps.planes[i].kind == PlaneKind::Tread && (!floor || ps.extents[i].z_mean < floor->z_mean)) floor = &ps.extents[i];
  ASSERT_NE(floor, nullptr);
  EXPECT_GT(floor->s_max, kFirstRiser + 0.5f) << "the floor's whole extent runs on beside the flight";
  const auto under = floor->strips.across(-0.4f, 0.4f), beside = floor->strips.across(0.6f, 5.0f);
  ASSERT_TRUE(under && beside);
  EXPECT_NEAR(under->second, kFirstRiser, 0.03f) << "under the flight it ends at the first riser";
  EXPECT_GT(beside->second, kFirstRiser + 0.5f);
  EXPECT_FALSE(floor->strips.across(5.0f, 6.0f)) << "no strip out there";
}

// The stair axis comes from the risers facing the camera, and a riser spans its flight. A flight's
// balusters (and posts, chair legs) are vertical strips facing the camera too, a few centimetres
// wide, turned towards it: seen beside a flight going down (no riser in view) they turned its axis
// 14 deg, and with a riser in view they pulled it off. A 1 m riser ahead and four 4 cm balusters
// to its left, each turned 40 deg towards the camera: the axis is the riser's.
TEST(PerceptionPlaneGeometry, BalustersFacingTheCameraDoNotTurnTheStairAxis) {
  const double a = 40 * M_PI / 180;
  std::vector<Rect> rects = {{{2.5, 0, -0.5}, {-1, 0, 0}, {0, 1, 0}, 0.5, 0.085}};
  for (int k = 0; k < 4; ++k)
    rects.push_back({{1.3 + 0.15 * k, 0.45, -0.3}, {-std::cos(a), -std::sin(a), 0}, {-std::sin(a), std::cos(a), 0}, 0.02, 0.4});
  const PlaneSet ps = planes_of(rects, -15, 3);  // the riser and balusters
  EXPECT_TRUE(ps.axis_from_risers);
  EXPECT_NEAR(ps.yaw_rad * 180 / M_PI, 0.0, 1.0);
}

// A flight's risers are parallel planes a tread apart, and none is taller than a rise. Walking 35 deg
// off a flight's axis, its side wall faces the camera at 55 deg, within the angle that lets a plane
// give the axis, and is the biggest plane in view: it gave the axis (50 deg), the risers were no
// risers for it, and no step was found in any frame. Three risers 0.28 m apart and a 2 m wall:
// the axis is the risers'.
TEST(PerceptionPlaneGeometry, ASideWallSeenObliquelyDoesNotTurnTheStairAxis) {
  const double a = 35 * M_PI / 180;
  const Eigen::Vector3d axis(std::cos(a), std::sin(a), 0), across(-std::sin(a), std::cos(a), 0);
  std::vector<Rect> rects;
  for (int k = 0; k < 3; ++k)
    rects.push_back({(1.6 + 0.28 * k) * axis + Eigen::Vector3d(0, 0, -0.915 + 0.17 * k), -axis, across, 0.5, 0.085});
  // The wall along the flight's right side, facing across it.
  rects.push_back({1.9 * axis - 0.65 * across + Eigen::Vector3d(0, 0, 0.0), across, axis, 1.5, 1.0});
  const PlaneSet ps = planes_of(rects, -30, 4);
  EXPECT_TRUE(ps.axis_from_risers);  // the risers' 35 deg below, not the wall's 55
  EXPECT_NEAR(ps.yaw_rad * 180 / M_PI, 35.0, 1.0);
}

// Nothing is seen through a surface: two pieces at one height with a lower surface seen between
// them along the stair are two surfaces. A box's top before a flight, at its first tread's height,
// had been merged with that tread into one 2.1 m "landing": the first step was lost and the model
// kept 8 false steps (a cluttered Kinect v2 ascent). The floor, a box 0.18 m high 1.2 m ahead and
// a first step of 0.18 m 2.2 m ahead: two treads at that height.
TEST(PerceptionPlaneGeometry, PiecesAtOneHeightWithTheFloorSeenBetweenAreTwoTreads) {
  const Eigen::Vector3d up(0, 0, 1), x(1, 0, 0), y(0, 1, 0);
  const std::vector<Rect> rects = {
      {{2.5, 0, -1.2}, up, x, 2.5, 1.5, y},          // the floor
      {{1.2, 0, -1.02}, up, x, 0.2, 0.3, y},         // the box's top
      {{1.0, 0, -1.11}, -x, y, 0.3, 0.09},           // its front
      {{2.2, 0, -1.11}, -x, y, 0.5, 0.09},           // the first riser
      {{2.35, 0, -1.02}, up, x, 0.15, 0.5, y}};      // the first tread
  const PlaneSet ps = planes_of(rects, -35, 4);
  int at_box_height = 0;
  for (const Plane& p : ps.planes) at_box_height += p.kind == PlaneKind::Tread && std::abs(p.centroid.z() + 1.02f) < 0.03f;
  EXPECT_EQ(at_box_height, 2);
}

// A surface shows only its front. A patch 0.2 m above a robot's camera whose
// fit leans 8 deg towards it (noise on a riser's top seen at a grazing angle
// did this on a D435) faces up within the tread tolerance, but an upward-facing
// surface above the eye is seen from its back: no tread. The same patch
// below the camera is one.
TEST(PerceptionPlaneGeometry, AnUpwardFacingPatchAboveTheCameraIsNoTread) {
  const double tilt = 8 * M_PI / 180;
  const Eigen::Vector3d n(-std::sin(tilt), 0, std::cos(tilt));  // world, towards the camera
  for (const double dz : {0.2, -0.2}) {
    DepthImage img;
    img.K = {320, 240, 262.5, 262.5, 159.5, 119.5};
    img.depth.assign(320 * 240, 0);
    const Eigen::Matrix3d R = test::optical_to_world(5, 0);
    const Eigen::Vector3d p0(2.6, 0, dz);
    for (int v = 0; v < 240; ++v)
      for (int u = 0; u < 320; ++u) {
        const Eigen::Vector3d ray_o((u - 159.5) / 262.5, (v - 119.5) / 262.5, 1.0), d = R * ray_o;
        const double t = p0.dot(n) / d.dot(n);  // along the optical ray, t = depth
        const Eigen::Vector3d x = t * d;
        if (t > 0 && std::abs(x.x() - p0.x()) < 0.3 && std::abs(x.y()) < 0.5)
          img.depth[static_cast<size_t>(v) * 320 + u] = static_cast<uint16_t>(t * 1000);
      }
    const PerceptionConfig cfg;
    NormalGrid grid;
    compute_normals(img, cfg.normals, grid);
    std::vector<int> labels;
    const std::vector<Segment> segments = grow_regions(grid, cfg.region_growing, 320, 240, labels);
    ASSERT_FALSE(segments.empty()) << dz;
    const PlaneSet ps = plane_geometry(grid, segments, R.cast<float>(), cfg.plane_geometry, cfg.output);
    const long treads = std::count_if(ps.planes.begin(), ps.planes.end(),
                                      [](const Plane& p) { return p.kind == PlaneKind::Tread; });
    EXPECT_EQ(treads, dz > 0 ? 0 : 1) << dz;
  }
}

// A riser's face is where its middle rows stand. Under a nosing overhang the slab's front (4 cm
// tall) stands 3 cm before the face and is merged into the same riser plane; the mean of its cells
// moved with how much of the slab the view held (a Kinect v2 ascent's per-frame treads 1-3 cm long
// where the next riser was seen differently). The floor, a riser face 1.23 m ahead under a slab
// whose front is at 1.2 m, and the tread on it, seen from 0.8 m up looking down 35 deg: the riser
// stands at its face (the mean of its cells lay 0.56 cm before it).
TEST(PerceptionPlaneGeometry, ARisersFaceIsItsMiddleNotTheNosingsSlab) {
  const Eigen::Vector3d up(0, 0, 1), x(1, 0, 0), y(0, 1, 0);
  const std::vector<Rect> rects = {
      {{0.8, 0, -0.8}, up, x, 0.43, 1.0, y},       // the floor, to the riser's foot
      {{1.23, 0, -0.735}, -x, y, 0.6, 0.065},      // the riser's face, 13 cm, under the slab
      {{1.2, 0, -0.65}, -x, y, 0.6, 0.02},         // the slab's front, 4 cm
      {{1.215, 0, -0.67}, -up, x, 0.015, 0.6, y},  // its underside (unseen from above)
      {{1.35, 0, -0.63}, up, x, 0.15, 0.6, y}};    // the tread
  const PlaneSet ps = planes_of(rects, -35, 3);
  int risers = 0;
  for (size_t i = 0; i < ps.planes.size(); ++i) {
    if (ps.planes[i].kind != PlaneKind::Riser) continue;
    ++risers;
    const float mean_s = ps.planes[i].centroid.x() * std::cos(ps.yaw_rad) + ps.planes[i].centroid.y() * std::sin(ps.yaw_rad);
    EXPECT_NEAR(ps.extents[i].s_mean, 1.23f, 0.004f);
    EXPECT_GT(ps.extents[i].z_max, -0.66f);  // the slab's front is in this plane
    EXPECT_LT(mean_s, 1.226f);               // and pulls the mean of its cells 0.4 cm or more forward
  }
  EXPECT_EQ(risers, 1);
}

// A riser's top is where the view of it stops only when nothing nearer hides it. Looking down past
// a coffee table at a sofa, the sofa's front showed under the table's top up to where the table's
// edge hid it: that edge drew a 0.23 m "riser" top, a level for the grammar, and a two-step
// staircase (a D435 hand-held walk towards a sofa). The floor 0.84 m below the camera, a box's
// front 0.35 m tall 3.2 m ahead, and a table top 0.42-0.45 m high from 2.2 to 2.7 m before it,
// wider than the box: the box's front is seen up to 0.22 m, its top out of view; without the
// table its top is in view.
TEST(PerceptionPlaneGeometry, ARisersTopHiddenByANearerSurfaceIsNotInView) {
  const Eigen::Vector3d up(0, 0, 1), x(1, 0, 0), y(0, 1, 0);
  std::vector<Rect> rects = {
      {{2.25, 0, -0.84}, up, x, 1.75, 1.5, y},  // the floor
      {{3.2, 0, -0.665}, -x, y, 0.5, 0.175},    // the box's front, 0.35 m
      {{3.5, 0, -0.49}, up, x, 0.3, 0.5, y}};   // its top
  const auto box_front = [](const PlaneSet& ps) {
    std::optional<PlaneExtent> front;
    for (size_t i = 0; i < ps.planes.size(); ++i)
      if (ps.planes[i].kind == PlaneKind::Riser && std::abs(ps.extents[i].s_mean - 3.2f) < 0.05f) front = ps.extents[i];
    return front;
  };
  const auto open = box_front(planes_of(rects, -25, 3));
  ASSERT_TRUE(open);
  EXPECT_NEAR(open->z_max, -0.49f, 0.03f);
  EXPECT_TRUE(open->top_in_view);
  rects.push_back({{2.45, 0, -0.39}, up, x, 0.25, 0.6, y});  // the table's top
  rects.push_back({{2.2, 0, -0.405}, -x, y, 0.6, 0.015});    // its front edge
  const auto hidden = box_front(planes_of(rects, -25, 4));
  ASSERT_TRUE(hidden);
  EXPECT_LT(hidden->z_max, -0.59f);  // seen up to where the table's edge hides it
  EXPECT_FALSE(hidden->top_in_view);
}

// A riser spans its step: a baluster facing the camera 7 cm before a riser, its foot 5 mm lower,
// was "the one reaching lowest" and stood for it (a robot's Kinect v1 on a flight with railings:
// runs of 17.8 and 32.2 cm for 25, and verification refused most frames).
TEST(PerceptionSteps, ABalusterBeforeARiserIsNotItsRiser) {
  PlaneSet ps = three_levels(0.3f, 1.0f, -1.0f);
  add_plane(ps, PlaneKind::Riser, {0.93f, 0.93f, -0.3f, -0.28f, -1.005f, -0.7f, 0.93f, -0.85f});
  const StairConfig cfg;
  const StairChain chain = best_chain(tread_levels(ps, {}, cfg), cfg);
  ASSERT_EQ(chain.direction, Direction::Up);
  const std::vector<Step> steps = steps_from_chain(ps, chain, cfg);
  ASSERT_EQ(steps.size(), 2u);
  EXPECT_EQ(steps[0].riser_plane, 3);
  EXPECT_NEAR(steps[0].nosing_m.x(), 1.0, 1e-4);
}

TEST(PerceptionReconstruction, ASliverOfRiserCutByTheViewIsTheNextStep) {
  // Looking up a flight: floor, two treads, and at the image's top edge 3 cm
  // of the next riser standing on the last tread (its top out of view).
  PlaneSet ps = three_levels(0.3f, 1.0f, -1.0f);
  PlaneExtent sliver{1.5f, 1.5f, -0.5f, 0.5f, -0.64f, -0.61f, 1.5f, -0.625f};
  sliver.top_in_view = false;
  add_plane(ps, PlaneKind::Riser, sliver);
  const StairConfig cfg;
  const StairChain chain = best_chain(tread_levels(ps, {}, cfg), cfg);
  ASSERT_EQ(chain.direction, Direction::Up);
  std::vector<Step> steps = steps_from_chain(ps, chain, cfg);
  ASSERT_EQ(steps.size(), 2u);
  reconstruct(ps, chain, steps, cfg);
  ASSERT_EQ(steps.size(), 3u);
  EXPECT_EQ(steps[2].riser_plane, 5);
  EXPECT_NEAR(steps[2].nosing_m.x(), 1.5, 1e-4);
  EXPECT_NEAR(steps[2].nosing_m.z(), -0.64 + 0.18, 1e-3);  // the rise is the chain's median
  EXPECT_NEAR(*steps[2].riser_height_m, 0.18, 1e-3);

  // Less than min_riser_seen_fraction of a rise in view is no step.
  ps.extents[5].z_max = ps.extents[5].z_min + 0.5f * cfg.min_riser_seen_fraction * 0.18f;
  steps = steps_from_chain(ps, chain, cfg);
  reconstruct(ps, chain, steps, cfg);
  EXPECT_EQ(steps.size(), 2u);
}

// A landing ends a flight: a surface rising at its far end with its top cut by
// the view is a back wall as much as the next flight's first riser, so nothing
// shows a step there until its top is seen. Nor is a cut surface a riser when
// its seen part alone is taller than any riser.
TEST(PerceptionReconstruction, ACutRiserBeyondALandingOrTallerThanAnyRiserIsNoStep) {
  const StairConfig cfg;
  // Floor, one tread, then a 1.5 m landing with a surface rising at its far end.
  PlaneSet ps = three_levels(0.3f, 1.0f, -1.0f);
  ps.extents[2].s_max = 2.75f;
  PlaneExtent wall{2.75f, 2.75f, -0.5f, 0.5f, -0.64f, -0.55f, 2.75f, -0.6f};
  wall.top_in_view = false;
  add_plane(ps, PlaneKind::Riser, wall);
  StairChain chain = best_chain(tread_levels(ps, {}, cfg), cfg);
  ASSERT_EQ(chain.direction, Direction::Up);
  std::vector<Step> steps = steps_from_chain(ps, chain, cfg);
  ASSERT_EQ(steps.size(), 2u);
  reconstruct(ps, chain, steps, cfg);
  EXPECT_EQ(steps.size(), 2u) << "a cut surface beyond a landing made a step";
  // Its top in view at a plausible rise: the next flight's first step, measured.
  ps.extents[5].top_in_view = true;
  ps.extents[5].z_max = -0.64f + 0.17f;
  steps = steps_from_chain(ps, chain, cfg);
  reconstruct(ps, chain, steps, cfg);
  ASSERT_EQ(steps.size(), 3u);
  EXPECT_NEAR(*steps[2].riser_height_m, 0.17, 1e-4);

  // A tread (no landing) with a cut surface whose seen part rises 0.4 m: a wall.
  ps = three_levels(0.3f, 1.0f, -1.0f);
  PlaneExtent tall{1.5f, 1.5f, -0.5f, 0.5f, -0.64f, -0.24f, 1.5f, -0.44f};
  tall.top_in_view = false;
  add_plane(ps, PlaneKind::Riser, tall);
  chain = best_chain(tread_levels(ps, {}, cfg), cfg);
  steps = steps_from_chain(ps, chain, cfg);
  reconstruct(ps, chain, steps, cfg);
  EXPECT_EQ(steps.size(), 2u) << "a cut surface taller than any riser made a step";
}

TEST(PerceptionReconstruction, ASliverOfRiserCutByTheBottomOfTheViewMakesTheFirstLevelAStep) {
  // Looking down a flight from above it: three treads, the risers between
  // them, and under the first tread's front edge 4 cm of its riser before the
  // image's lower border (the tread below is out of view).
  PlaneSet ps = three_levels(0.4f, 0.65f, -0.6f);
  PlaneExtent sliver{0.4f, 0.4f, -0.5f, 0.5f, -0.64f, -0.6f, 0.4f, -0.62f};
  sliver.bottom_in_view = false;
  add_plane(ps, PlaneKind::Riser, sliver);
  const StairConfig cfg;
  const StairChain chain = best_chain(tread_levels(ps, {}, cfg), cfg);
  ASSERT_EQ(chain.direction, Direction::Up);
  std::vector<Step> steps = steps_from_chain(ps, chain, cfg);
  ASSERT_EQ(steps.size(), 2u);
  reconstruct(ps, chain, steps, cfg);
  ASSERT_EQ(steps.size(), 3u);
  EXPECT_EQ(steps[0].riser_plane, 5);
  EXPECT_NEAR(steps[0].nosing_m.x(), 0.4, 1e-4);
  EXPECT_NEAR(*steps[0].riser_height_m, 0.18, 1e-3);  // the chain's median, flagged
  EXPECT_TRUE(steps[0].inferred & kStepRiserInferred);

  // The same 4 cm with its bottom in view is a riser that short, no step's.
  ps.extents[5].bottom_in_view = true;
  steps = steps_from_chain(ps, chain, cfg);
  reconstruct(ps, chain, steps, cfg);
  EXPECT_EQ(steps.size(), 2u);
  // Cut by the border, less than min_riser_seen_fraction of a rise is no step either.
  ps.extents[5].bottom_in_view = false;
  ps.extents[5].z_min = ps.extents[5].z_max - 0.5f * cfg.min_riser_seen_fraction * 0.18f;
  steps = steps_from_chain(ps, chain, cfg);
  reconstruct(ps, chain, steps, cfg);
  EXPECT_EQ(steps.size(), 2u);
}

}  // namespace
}  // namespace stairs
