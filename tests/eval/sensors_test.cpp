// Accuracy on every sensor model of stairs-sim (Kinect v1 structured light,
// Kinect v2 time of flight, RealSense D4xx stereo) and the presets of what
// broke on data nobody here made (issue 14): the real stairs-sim program writes
// each walk as an LCM log, the offline chain (tools/replay) scores it.
// Floors: the final model holds every real step, no false step in any frame or
// in the model, mean absolute riser and tread error <= 0.5 cm.
#include "tools/replay.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <optional>

namespace stairs {
namespace {

namespace fs = std::filesystem;

struct Walk {
  const char* name;  // test name: <case>_<sensor>
  const char* args;  // stairs-sim options
  int seed = 5;      // stairs-sim --seed (a randomised walk's own, to replay what it found)
};

void PrintTo(const Walk& w, std::ostream* os) { *os << w.args; }

std::string print(const eval::ErrorStats& e) { return e.mean_abs ? std::to_string(*e.mean_abs) : "n/a"; }

class SensorAccuracy : public ::testing::TestWithParam<Walk> {};

// The walk written by the real stairs-sim as a 10 Hz LCM log and scored through the offline chain.
std::optional<eval::Score> score_walk(const Walk& w) {
  const fs::path log = fs::path(STAIRS_BINARY_DIR) / "sensor-logs" / (std::string(w.name) + ".lcmlog");
  fs::create_directories(log.parent_path());
  const std::string cmd = std::string(STAIRS_BINARY_DIR) + "/bin/stairs-sim " + w.args +
                          " --fps 10 --seed " + std::to_string(w.seed) + " --log '" + log.string() + "' > /dev/null";
  if (std::system(cmd.c_str()) != 0) {
    ADD_FAILURE() << cmd;
    return std::nullopt;
  }
  const eval::RunResult r = eval::replay(log.string(), {});
  fs::remove(log);
  return r.score;
}

// The final model holds every real step, no false one, and its mean absolute riser and tread errors are
// within half a centimetre.
void expect_model_within_half_a_centimetre(const eval::Score& s, const char* name) {
  EXPECT_EQ(s.model_steps_detected, s.model_steps_real) << name;
  EXPECT_EQ(s.model_false_steps, 0) << name;
  ASSERT_TRUE(s.riser_error_cm.mean_abs && s.tread_error_cm.mean_abs) << name;
  EXPECT_LE(*s.riser_error_cm.mean_abs, 0.5) << name;
  EXPECT_LE(*s.tread_error_cm.mean_abs, 0.5) << name;
}

TEST_P(SensorAccuracy, EveryStepWithinHalfACentimetreNoFalseStepAndTheCameraWithinTwo) {
  const Walk& w = GetParam();
  const std::optional<eval::Score> scored = score_walk(w);
  ASSERT_TRUE(scored) << w.name;
  const eval::Score& s = *scored;
  std::printf("%s: model %d/%d, riser %s cm, tread %s cm, false %d/%d, detection nosing in view %.1f %%, tracked %.1f %%\n",
              w.name, s.model_steps_detected, s.model_steps_real, print(s.riser_error_cm).c_str(),
              print(s.tread_error_cm).c_str(), s.frame_false_steps, s.model_false_steps,
              100 * s.frame_step_detection_nosing_in_view.value_or(0), 100 * s.frame_step_detection_tracked.value_or(0));
  expect_model_within_half_a_centimetre(s, w.name);
  EXPECT_EQ(s.frame_false_steps, 0) << w.name;
  // Where the camera is along the stair (issue 15), to within 2 cm on average. The model's nosings
  // stood at the risers' faces, 3 cm behind a nosing overhang's edge: the steep ascents were 2.4-3.0
  // cm off and took the wrong step beneath near each edge.
  ASSERT_TRUE(s.tracked_position_error_cm.mean_abs) << w.name;
  EXPECT_LE(*s.tracked_position_error_cm.mean_abs, 2.0) << w.name;
}

#define STAIRS_WALKS(sensor)                                                                                   \
  Walk{"straight_up_" #sensor, "--preset straight_up --sensor " #sensor},                                        \
      Walk{"straight_down_" #sensor, "--preset straight_down --sensor " #sensor},                                \
      Walk{"up_robot_" #sensor, "--preset straight_up --carrier robot --sensor " #sensor},                       \
      Walk{"steep_nosing_down_" #sensor, "--preset steep_nosing --direction down --sensor " #sensor}

const auto kName = [](const auto& info) { return std::string(info.param.name); };

INSTANTIATE_TEST_SUITE_P(Sim, SensorAccuracy,
                         ::testing::Values(
                             STAIRS_WALKS(kinect1), STAIRS_WALKS(d435),
                             Walk{"straight_up_kinect2", "--preset straight_up --sensor kinect2"},
                             Walk{"straight_down_kinect2", "--preset straight_down --sensor kinect2"},
                             Walk{"steep_nosing_down_kinect2", "--preset steep_nosing --direction down --sensor kinect2"},
                             Walk{"steep_nosing_up_kinect1", "--preset steep_nosing --sensor kinect1"},
                             Walk{"steep_nosing_up_kinect2", "--preset steep_nosing --sensor kinect2"},
                             Walk{"level_09m_kinect1", "--preset straight_up --height 0.9 --pitch 0 --situation approach "
                                                       "--sensor kinect1"},
                             Walk{"level_09m_d435", "--preset straight_up --height 0.9 --pitch 0 --situation approach "
                                                    "--sensor d435"},
                             Walk{"level_09m_kinect2", "--preset straight_up --height 0.9 --pitch 0 "
                                                       "--situation approach --sensor kinect2"},
                             Walk{"dark_treads_kinect1", "--preset dark_treads --sensor kinect1"},
                             Walk{"dark_treads_d435", "--preset dark_treads --sensor d435"},
                             // With no tread segmented, each riser's top and the rims of the holes in its
                             // dark tread were separate levels, so a tread between two risers read as one
                             // 45 cm tread and 3 frames showed a false step; one surface is one level now.
                             Walk{"dark_treads_kinect2", "--preset dark_treads --sensor kinect2"},
                             Walk{"irregular_step_kinect1", "--preset irregular_step --sensor kinect1"},
                             Walk{"irregular_step_kinect2", "--preset irregular_step --sensor kinect2"},
                             Walk{"irregular_step_d435", "--preset irregular_step --sensor d435"},
                             Walk{"steep_nosing_up_d435", "--preset steep_nosing --sensor d435"},
                             Walk{"up_robot_kinect2", "--preset straight_up --carrier robot --sensor kinect2"},
                             // Open risers going down: each step a 4 cm tread slab on nothing. From above
                             // the gaps beneath the nosings are out of sight, as risers are.
                             Walk{"open_risers_down_kinect1", "--preset open_risers --direction down --sensor kinect1"},
                             Walk{"open_risers_down_kinect2", "--preset open_risers --direction down --sensor kinect2"},
                             Walk{"open_risers_down_d435", "--preset open_risers --direction down --sensor d435"},
                             Walk{"open_risers_down_robot_d435",
                                  "--preset open_risers --direction down --carrier robot --sensor d435"},
                             // Furniture beside the flight's foot (stairs-sim --furniture), in view beside
                             // the true steps: a kitchen table with chairs, a sofa, a counter with bar
                             // stools, a desk; their seats and tops add no step and take none away.
                             Walk{"kitchen_table_beside_up_kinect1", "--preset open_sides --furniture kitchen_table "
                                  "--yaw 15 --lateral 0.3 --sensor kinect1"},
                             Walk{"sofa_beside_up_kinect2", "--preset open_sides --furniture sofa --yaw 15 --lateral 0.3 "
                                  "--sensor kinect2"},
                             Walk{"counter_stools_beside_robot_d435", "--preset open_sides --furniture counter_stools "
                                  "--carrier robot --yaw 15 --sensor d435"},
                             Walk{"desk_beside_down_kinect1", "--preset open_sides --furniture desk --direction down "
                                  "--sensor kinect1"},
                             // Walking down turned 12 deg from the flight, 0.2 m off its centre line: the
                             // risers are hidden, so the nosings' lines give the stair axis (without them
                             // treads came out 0.9-1.1 cm short and Kinect v1 kept a false model step).
                             Walk{"yawed_down_kinect1",
                                  "--preset straight_down --yaw 12 --lateral -0.2 --sensor kinect1"},
                             Walk{"yawed_down_kinect2",
                                  "--preset straight_down --yaw 12 --lateral -0.2 --sensor kinect2"},
                             Walk{"yawed_down_d435",
                                  "--preset straight_down --yaw 12 --lateral -0.2 --sensor d435"},
                             // Balusters beside a flight going down (no riser in view) are strips facing
                             // the camera: they gave the stair axis, 14 deg off, and the tracker placed the
                             // camera up to 60 cm off for 13 s (Kinect v2; a D435 for 2 s).
                             Walk{"railings_down_kinect2", "--preset railings --direction down --sensor kinect2"},
                             Walk{"railings_down_d435", "--preset railings --direction down --sensor d435"},
                             // The top of the head of a person at the foot of the flight, 10 cm below the
                             // top landing and 4 m ahead, was taken for the level after the landing: the
                             // chain went down from the first step and the model never had the landing's edge.
                             Walk{"people_down_kinect1", "--preset people --direction down --sensor kinect1"},
                             Walk{"people_down_kinect2", "--preset people --direction down --sensor kinect2"},
                             // A randomised walk (seed 74 presets, 21): after 0.4 s without steps, the frame
                             // showing the mid landing's edge and the next flight's first nosing fitted a
                             // whole step back best (the new flight's points then lay on the model), and the
                             // second flight was re-seeded onto the first (8 of 14 model steps, 184 frames
                             // with false tracked steps): a search no farther than the prior may be off.
                             Walk{"two_flights_up_kinect1", "--preset two_flights --direction up --sensor kinect1 "
                                  "--carrier handheld --height 0.97 --pitch -38.4 --lateral -0.02 --yaw -2.6", 86079},
                             // Walking 30-35 deg off the flight's axis, the side wall faces the camera as
                             // much as the risers do and is the biggest plane in view: it gave the stair axis
                             // (going up, the risers were no risers for it) and, going down, kept the nosings
                             // out of the lines searched for the axis. No step in any frame before.
                             Walk{"oblique_up_kinect1", "--preset straight_up --yaw 35 --sensor kinect1", 3},
                             Walk{"oblique_down_kinect1", "--preset straight_down --yaw -30 --sensor kinect1", 4},
                             Walk{"oblique_down_kinect2", "--preset straight_down --yaw 35 --sensor kinect2", 3},
                             // A robot's camera on a 1.1 m mast (no mount configured), rocking 10 cm along the
                             // stair between frames as the body pitches over the nosings: a whole-step search
                             // put it a step back four frames in a row and the velocity then carried it up
                             // the stair a step a frame while it went down (34 false model steps before).
                             Walk{"mast_down_kinect1", "--preset nosing --direction down --carrier robot --height 1.1 "
                                  "--pitch -45 --sensor kinect1", 7},
                             // A randomised walk (seed 81 --presets --wide, 11): a box's top before the flight,
                             // at its first tread's height, made one 2.1 m "landing" with that tread (the
                             // floor seen between them): the first step was lost, 8 false model steps.
                             Walk{"box_before_flight_kinect2", "--preset cluttered --direction up --sensor kinect2 "
                                  "--carrier handheld --height 1.49 --pitch -22.2 --roll 3.3 --lateral 0.01 "
                                  "--yaw -26.7", 9867},
                             // A randomised walk (seed 81 --presets --wide, 09): a robot's camera 0.92 m up
                             // swings 20 cm in a frame as the body rocks over a nosing; near the foot, ICP
                             // from the prior fitted the flight a step low and the model grew 2 false steps
                             // below its first, on the floor it had seen there.
                             Walk{"mast_railings_down_d435", "--preset railings --direction down --sensor d435 "
                                  "--carrier robot --height 0.92 --pitch -32.6 --lateral -0.11 --yaw 6.0", 2447},
                             // Dark treads return nothing on half their pixels at random. Counted against
                             // the cell's area, half their cells had no point: a Kinect v2 walking 32 deg
                             // off the axis (seed 81 --presets --wide, 08) segmented too little of them for
                             // concave_corners to find the risers' multipath bands (risers 0.59 cm off, 2
                             // frames with false steps); a D435 robot descent's treads 0.53 cm off.
                             Walk{"dark_oblique_up_kinect2", "--preset dark_treads --direction up --sensor kinect2 "
                                  "--carrier handheld --height 1.30 --pitch -38.3 --roll -7.4 --lateral 0.16 "
                                  "--yaw -32.2", 69036},
                             Walk{"dark_down_d435_robot", "--preset dark_treads --direction down --sensor d435 "
                                  "--carrier robot --lateral 0.10 --yaw 10.6", 4599},
                             // A randomised walk (seed 71, 11): a Kinect v2 robot below 3 cm nosing
                             // overhangs. Where the recessed riser meets the slab's front, 4 cm below the
                             // tread, cells face up: a band across the riser's face was taken for the
                             // tread, and the model's second rise came out 2.6 cm short (risers 1.17 cm).
                             // A randomised walk (seed 164 --presets --wide, 23): a Kinect v1 robot at the
                             // second flight's foot rocked 13 cm back while the prior carried it on; after
                             // 0.5 s of frames turned down, that refuted prior told apart the whole-step
                             // shifts that fit the few steps in view alike: a step up (a false model step
                             // above the top landing).
                             Walk{"two_flights_lurch_up_kinect1_robot", "--preset two_flights --direction up "
                                  "--sensor kinect1 --carrier robot --height 0.76 --pitch -44.2 --lateral 0.21 "
                                  "--yaw 5.2", 23724},
                             // A randomised walk (seed 144 --presets --wide, 23): a Kinect v1 robot's camera
                             // 0.79 m up swung 25 cm back at about the same height as its body pitched up over
                             // a nosing, while the prior carried it on. The whole-step search started only on
                             // the stair's slope from there: those starts a tread back lay 10 cm too low, ICP
                             // took the tread below, and the one good fit, a whole step up, was taken for
                             // unambiguous: a false model step above the second flight.
                             Walk{"two_flights_swing_up_kinect1_robot", "--preset two_flights --direction up "
                                  "--sensor kinect1 --carrier robot --height 0.79 --pitch -38.3 --lateral -0.08 "
                                  "--yaw -37.4", 97331},
                             // A randomised walk (seed 154 --presets --wide, 23): a Kinect v1 robot's body
                             // pitched up at the first flight's foot; for one frame its camera saw only the
                             // next flight, which the motion prior placed 5.3 cm off. Registered on that flight
                             // from then on, the camera stayed 5.3 cm off along the first for 13 s (the step
                             // beneath it wrong at every nosing: 95.4 %), until a frame that saw both flights
                             // measured the offset (tracker/prior_links.hpp).
                             Walk{"two_flights_glimpse_up_kinect1_robot", "--preset two_flights --direction up "
                                  "--sensor kinect1 --carrier robot --height 1.14 --pitch -43.4 --lateral -0.24 "
                                  "--yaw -15.8", 36532},
                             Walk{"nosing_band_up_kinect2_robot", "--preset straight_up --steps 4 --riser 0.198 "
                                  "--tread 0.278 --width 0.96 --nosing 0.029 --walls none --sensor kinect2 "
                                  "--carrier robot --lateral -0.24 --yaw -3.9", 52265},
                             // A randomised walk (seed 176 --wide, 15): a hand-held Kinect v2 walking up to a
                             // descent. Each tread seen from above lies between two depth jumps, and its
                             // edge cells mixed with the surfaces beyond them tilted it 2-8 deg; once the
                             // floor left the view the treads set the pitch 1-3 deg off: 18 frames with
                             // false steps, the tracked camera 23 cm off on average.
                             Walk{"descent_flying_pixels_kinect2", "--preset straight_down --steps 11 --riser 0.164 "
                                  "--tread 0.228 --width 1.73 --nosing 0.025 --walls left --sensor kinect2 "
                                  "--carrier handheld --height 1.31 --pitch -22.1 --roll -3.6 --lateral -0.20 "
                                  "--yaw 0.3", 44605}),
                         kName);

// Walks this chain cannot yet model whole (their floors are not met), where what it does give must
// still hold no false step: unknown, not wrong.
class SensorHonesty : public ::testing::TestWithParam<Walk> {};

// No false step in any frame or in the model: unknown, not wrong.
void expect_no_false_step(const eval::Score& s, const char* name) {
  std::printf("%s: model %d/%d, false %d/%d, detection nosing in view %.1f %%\n", name, s.model_steps_detected,
              s.model_steps_real, s.frame_false_steps, s.model_false_steps,
              100 * s.frame_step_detection_nosing_in_view.value_or(0));
  EXPECT_EQ(s.model_false_steps, 0) << name;
  EXPECT_EQ(s.frame_false_steps, 0) << name;
}

TEST_P(SensorHonesty, NoFalseStepInAnyFrameOrInTheModel) {
  const Walk& w = GetParam();
  const std::optional<eval::Score> scored = score_walk(w);
  ASSERT_TRUE(scored) << w.name;
  expect_no_false_step(*scored, w.name);
  EXPECT_GT(scored->model_steps_detected, 0) << w.name << ": nothing modelled, no test";
}

INSTANTIATE_TEST_SUITE_P(Sim, SensorHonesty,
                         ::testing::Values(
                             // A randomised walk (seed 174 --presets --wide, 23): a hand-held Kinect v1 going
                             // down two flights sees the lower one first, then nothing it can take the pitch
                             // from for a second (the model is lost), then the upper one, which the model does
                             // not hold. Whole-step search starts level with a lost stair's stale prior fitted
                             // the upper flight onto the lower one on 3 risers and nosings: 4 false model steps.
                             Walk{"two_flights_lost_down_kinect1", "--preset two_flights --direction down "
                                  "--sensor kinect1 --carrier handheld --height 1.18 --pitch -22.3 --roll 4.5 "
                                  "--lateral 0.07 --yaw -18.0", 18942}),
                         kName);

// Open risers going up: under each nosing the camera sees through to the floor beneath the flight,
// the evidence verification takes for a chair seat or a table (no riser under the nosing, issue 14),
// so the flight is no staircase in most frames and the model stays empty or partial. What is given
// must hold no false step: unknown, not wrong.
class OpenRisersUp : public ::testing::TestWithParam<Walk> {};

TEST_P(OpenRisersUp, NoFalseStepInAnyFrameOrInTheModel) {
  const Walk& w = GetParam();
  const std::optional<eval::Score> scored = score_walk(w);
  ASSERT_TRUE(scored) << w.name;
  ASSERT_GT(scored->model_steps_real, 0) << w.name << ": no stair in the walk, no test";
  expect_no_false_step(*scored, w.name);
}

INSTANTIATE_TEST_SUITE_P(Sim, OpenRisersUp,
                         ::testing::Values(Walk{"open_risers_up_kinect1", "--preset open_risers --sensor kinect1"},
                                           Walk{"open_risers_up_kinect2", "--preset open_risers --sensor kinect2"},
                                           Walk{"open_risers_up_d435", "--preset open_risers --sensor d435"},
                                           Walk{"open_risers_up_robot_d435",
                                                "--preset open_risers --carrier robot --sensor d435"}),
                         kName);

// Walks where perception gives false steps in a few frames (a D435's nosings 3 m away), whose model
// must still hold every real step within half a centimetre and no false one: one odd frame leaves
// no step in the model (issue 14).
class SensorModel : public ::testing::TestWithParam<Walk> {};

TEST_P(SensorModel, EveryRealStepWithinHalfACentimetreAndNoFalseOne) {
  const Walk& w = GetParam();
  const std::optional<eval::Score> scored = score_walk(w);
  ASSERT_TRUE(scored) << w.name;
  const eval::Score& s = *scored;
  std::printf("%s: model %d/%d, riser %s cm, tread %s cm, false %d/%d\n", w.name, s.model_steps_detected,
              s.model_steps_real, print(s.riser_error_cm).c_str(), print(s.tread_error_cm).c_str(),
              s.frame_false_steps, s.model_false_steps);
  expect_model_within_half_a_centimetre(s, w.name);
}

INSTANTIATE_TEST_SUITE_P(Sim, SensorModel,
                         ::testing::Values(
                             // A randomised walk (seed 195 --level, 08): a hand-held D435 at 1.47 m, nearly
                             // level, walking to a descent 2.5 m away. Its first frame measured the nosings
                             // 3 m away 9 cm high; the next frame's steps, matching none of them, were added
                             // beside them by a motion prior that had no velocity yet, and a wrong model
                             // grew on both: 5 false model steps, the tracked camera 8.9 cm off in height.
                             Walk{"level_descent_far_seed_d435", "--preset straight_down --steps 11 --riser 0.136 "
                                  "--tread 0.330 --width 0.95 --nosing 0.000 --walls right --sensor d435 "
                                  "--carrier handheld --height 1.47 --pitch -14.5 --lateral 0.19 --yaw -14.7", 6079}),
                         kName);

}  // namespace
}  // namespace stairs
