// Accuracy floors of the perception and tracker issues on the committed sample
// logs, through the real stairs-eval program. Scores and ratios only.
#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::vector<std::string> sample_logs() {
  std::vector<std::string> out;
  const fs::path dir = fs::path(STAIRS_SOURCE_DIR) / "logs";
  if (fs::is_directory(dir))
    for (const auto& e : fs::directory_iterator(dir))
      if (e.path().extension() == ".lcmlog") out.push_back(e.path().stem().string());
  std::sort(out.begin(), out.end());
  return out;
}

double num(const json& j) { return j.is_number() ? j.get<double>() : std::nan(""); }

// The log under test: its stem, from the environment (one ctest test per log,
// see CMakeLists.txt).
std::string log_under_test() {
  const char* name = std::getenv("STAIRS_EVAL_LOG");
  return name ? name : "";
}

json run_eval(const std::string& name) {
  const fs::path log = fs::path(STAIRS_SOURCE_DIR) / "logs" / (name + ".lcmlog");
  // One file per test: ctest runs the tests of one log side by side.
  const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
  const fs::path out = fs::path(STAIRS_BINARY_DIR) / "eval-results" / (name + "." + test + ".json");
  fs::create_directories(out.parent_path());
  fs::remove(out);
  // A config for the run (the robot logs' mount), from the environment (CMakeLists.txt).
  const char* config = std::getenv("STAIRS_EVAL_CONFIG");
  const std::string cmd = std::string(STAIRS_BINARY_DIR) + "/bin/stairs-eval --quiet --json '" + out.string() +
                          "' '" + log.string() + "'" + (config ? std::string(" --config '") + config + "'" : "");
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  std::ifstream in(out);
  if (!in) return {};
  return json::parse(in);
}

TEST(EvalLogsPresent, SampleLogsCommitted) {
  EXPECT_FALSE(sample_logs().empty()) << "no logs/*.lcmlog: the accuracy floors cannot be checked";
}

json score_of_log_under_test() {
  const std::string name = log_under_test();
  if (name.empty()) ADD_FAILURE() << "STAIRS_EVAL_LOG not set";
  const json r = name.empty() ? json() : run_eval(name);
  if (!r.is_object()) ADD_FAILURE() << name << ": stairs-eval wrote no Result JSON";
  else if (!r["score"].is_object()) ADD_FAILURE() << name << ": no ground truth in the log";
  return r.is_object() ? r["score"] : json();
}

// Per-frame detection, issue 15's floors: perception over the visible steps
// whose nosing is in the image (DESIGN.md frame_step_detection_nosing_in_view)
// and the tracked model from its camera over all visible steps
// (frame_step_detection_tracked), each >= 95 %; the all-visible figure is
// printed beside them. Tests of their own so that a log missing only these
// still has every other floor checked (CMakeLists.txt lists where they are not
// met yet).
TEST(EvalLogs, PerceptionDetectionFloor) {
  const json s = score_of_log_under_test();
  ASSERT_TRUE(s.is_object());
  const std::string log = log_under_test() + ": ";
  if (num(s["model_steps_real"]) > 0) {
    EXPECT_GE(num(s["frame_step_detection_nosing_in_view"]), 0.95)
        << log << "FLOOR(perception) per-frame detection of the steps whose nosing is in view "
        << s["frame_step_detection_nosing_in_view"] << " (of " << s["visible_steps_nosing_in_view"]
        << "; of all visible steps " << s["frame_step_detection"] << ") < 95%";
  } else {
    EXPECT_EQ(num(s["false_steps"]["frames"]), 0)
        << log << "FLOOR(perception) false steps on a non-stair scene: " << s["false_steps"];
  }
}

TEST(EvalLogs, TrackedDetectionFloor) {
  const json s = score_of_log_under_test();
  ASSERT_TRUE(s.is_object());
  const std::string log = log_under_test() + ": ";
  if (num(s["model_steps_real"]) > 0) {
    EXPECT_GE(num(s["frame_step_detection_tracked"]), 0.95)
        << log << "FLOOR(tracker) per-frame detection of the tracked model from its camera "
        << s["frame_step_detection_tracked"] << " (" << s["frame_steps_matched_tracked"] << " of "
        << s["visible_steps"] << " visible steps) < 95%";
  } else {
    EXPECT_EQ(num(s["false_steps"]["frames_tracked"]), 0)
        << log << "FLOOR(tracker) false steps on a non-stair scene: " << s["false_steps"];
  }
}

// Every other floor, each a separate EXPECT naming the issue it comes from, so
// one run reports all the figures that miss.
TEST(EvalLogs, AccuracyFloors) {
  const json s = score_of_log_under_test();
  ASSERT_TRUE(s.is_object());
  const bool stairs = num(s["model_steps_real"]) > 0;
  const std::string log = log_under_test() + ": ";

  EXPECT_EQ(num(s["false_steps"]["frames"]), 0)
      << log << "FLOOR(perception) false steps: " << s["false_steps"];
  EXPECT_LE(num(s["pitch_error_deg"]), 1.0) << log << "FLOOR(perception) pitch error " << s["pitch_error_deg"] << " deg";
  EXPECT_LE(num(s["roll_error_deg"]), 1.0) << log << "FLOOR(perception) roll error " << s["roll_error_deg"] << " deg";
  // The floor holds where the floor or a tread beneath is in view
  // and perception gives a height (it gives none where the frame cannot show
  // the surface is beneath, e.g. in a room without a stair).
  if (num(s["height_frames_beneath_visible"]) > 0) {
    EXPECT_LE(num(s["height_error_beneath_visible_cm"]), 3.0)
        << log << "FLOOR(perception) height error " << s["height_error_beneath_visible_cm"] << " cm over "
        << s["height_frames_beneath_visible"] << " frames with the surface beneath in view";
  }

  EXPECT_EQ(num(s["model_steps_detected"]), num(s["model_steps_real"]))
      << log << "FLOOR(tracker) model holds " << s["model_steps_detected"] << " of " << s["model_steps_real"]
      << " real steps";
  EXPECT_EQ(num(s["false_steps"]["model"]), 0) << log << "FLOOR(tracker) false steps in the model: "
                                               << s["false_steps"]["model"];
  EXPECT_EQ(num(s["false_steps"]["frames_tracked"]), 0)
      << log << "FLOOR(tracker) false steps in the model seen from its camera: " << s["false_steps"];
  if (stairs) {
    EXPECT_LE(num(s["riser_error_cm"]["mean_abs"]), 1.0)
        << log << "FLOOR(tracker) riser error " << s["riser_error_cm"] << " cm";
    EXPECT_LE(num(s["tread_error_cm"]["mean_abs"]), 1.0)
        << log << "FLOOR(tracker) tread error " << s["tread_error_cm"] << " cm";
  }
}

// Issue 15: where the camera is on every frame. Perception's height, where it
// gives one, within 2 cm on average (without a mount, only where the frame
// shows the surface beneath); the tracker's camera (stairs-eval's
// tracked_camera) within 2 cm above the surface beneath and on the right step
// in >= 98 % of the frames where it is valid. A test of its own so that a log
// missing one of these still has every other floor checked.
TEST(EvalLogs, CameraFloors) {
  const json s = score_of_log_under_test();
  ASSERT_TRUE(s.is_object());
  const std::string log = log_under_test() + ": ";
  if (num(s["height_frames"]) > 0) {
    EXPECT_LE(num(s["height_error_cm"]), 2.0) << log << "FLOOR(perception) height error " << s["height_error_cm"]
                                              << " cm over " << s["height_frames"] << " frames with a height";
  }
  if (num(s["model_steps_real"]) > 0) {
    EXPECT_GT(num(s["tracked_camera_frames"]), 0) << log << "FLOOR(tracker) no frame with a tracked camera";
    EXPECT_LE(num(s["tracked_height_error_cm"]), 2.0)
        << log << "FLOOR(tracker) camera height error " << s["tracked_height_error_cm"] << " cm";
    EXPECT_GE(num(s["tracked_step_index_accuracy"]), 0.98)
        << log << "FLOOR(tracker) step beneath the camera right in " << s["tracked_step_index_accuracy"]
        << " of " << s["tracked_camera_frames"] << " frames";
  }
}

// Issue 15, the mount: with stairs-sim's robot mount configured
// (config/stairs-sim-robot.json), perception names the level at the mount's
// height below the level robot as its ground, where no frame shows it beneath:
// a height on the frames on level ground, within 2 cm on average, and none on
// the flight (the robot tilts).
TEST(EvalLogs, MountedCameraHeight) {
  ASSERT_NE(std::getenv("STAIRS_EVAL_CONFIG"), nullptr) << "STAIRS_EVAL_CONFIG not set (CMakeLists.txt)";
  const json s = score_of_log_under_test();
  ASSERT_TRUE(s.is_object());
  const std::string log = log_under_test() + ": ";
  EXPECT_GE(num(s["height_frames"]), 20) << log << "FLOOR(perception) " << s["height_frames"]
                                         << " frames with a height on the mounted robot";
  EXPECT_LE(num(s["height_error_cm"]), 2.0) << log << "FLOOR(perception) height error " << s["height_error_cm"]
                                            << " cm over " << s["height_frames"] << " frames with a height";
}

// Issue 15, outputs in the robot's base frame: with the robot's mount configured the tracker gives
// its base (the camera carried back through the mount) as well as the camera, each within 2 cm above
// the surface beneath and on the right step in >= 98 % of the frames where it is valid. The base is
// scored against stairs-sim's rigid robot (drivers/sim/trajectory.hpp).
TEST(EvalLogs, MountedTrackedBaseAndCamera) {
  ASSERT_NE(std::getenv("STAIRS_EVAL_CONFIG"), nullptr) << "STAIRS_EVAL_CONFIG not set (CMakeLists.txt)";
  const json s = score_of_log_under_test();
  ASSERT_TRUE(s.is_object());
  const std::string log = log_under_test() + ": ";
  EXPECT_GT(num(s["tracked_camera_frames"]), 0) << log << "FLOOR(tracker) no frame with a tracked camera";
  EXPECT_LE(num(s["tracked_height_error_cm"]), 2.0)
      << log << "FLOOR(tracker) camera height error " << s["tracked_height_error_cm"] << " cm";
  EXPECT_GE(num(s["tracked_step_index_accuracy"]), 0.98)
      << log << "FLOOR(tracker) step beneath the camera right in " << s["tracked_step_index_accuracy"];
  EXPECT_EQ(num(s["tracked_base_frames"]), num(s["tracked_camera_frames"]))
      << log << "FLOOR(tracker) a base on every frame with a camera: " << s["tracked_base_frames"];
  EXPECT_LE(num(s["tracked_base_height_error_cm"]), 2.0)
      << log << "FLOOR(tracker) base height error " << s["tracked_base_height_error_cm"] << " cm";
  EXPECT_GE(num(s["tracked_base_step_index_accuracy"]), 0.98)
      << log << "FLOOR(tracker) step beneath the base right in " << s["tracked_base_step_index_accuracy"];
}

}  // namespace
