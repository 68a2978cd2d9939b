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
  const fs::path out = fs::path(STAIRS_BINARY_DIR) / "eval-results" / (name + ".json");
  fs::create_directories(out.parent_path());
  fs::remove(out);
  const std::string cmd = std::string(STAIRS_BINARY_DIR) + "/bin/stairs-eval --quiet --json '" + out.string() +
                          "' '" + log.string() + "'";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  std::ifstream in(out);
  if (!in) return {};
  return json::parse(in);
}

TEST(EvalLogsPresent, SampleLogsCommitted) {
  EXPECT_FALSE(sample_logs().empty()) << "no logs/*.lcmlog: the accuracy floors cannot be checked";
}

// Every floor is a separate EXPECT naming the issue it comes from, so one run
// reports all the figures that miss.
TEST(EvalLogs, AccuracyFloors) {
  const std::string name = log_under_test();
  ASSERT_FALSE(name.empty()) << "STAIRS_EVAL_LOG not set";
  const json r = run_eval(name);
  ASSERT_TRUE(r.is_object()) << "stairs-eval wrote no Result JSON";
  const json& s = r["score"];
  ASSERT_TRUE(s.is_object()) << name << ": no ground truth in the log";
  const bool stairs = num(s["model_steps_real"]) > 0;
  const std::string log = name + ": ";

  if (stairs) {
    EXPECT_GE(num(s["frame_step_detection"]), 0.90)
        << log << "FLOOR(perception) per-frame detection " << s["frame_step_detection"] << " ("
        << s["frame_steps_matched"] << " of " << s["visible_steps"] << " visible steps) < 90%";
  } else {
    EXPECT_EQ(num(s["false_steps"]["frames"]), 0)
        << log << "FLOOR(perception) false steps on a non-stair scene: " << s["false_steps"];
  }
  EXPECT_LE(num(s["pitch_error_deg"]), 1.0) << log << "FLOOR(perception) pitch error " << s["pitch_error_deg"] << " deg";
  EXPECT_LE(num(s["roll_error_deg"]), 1.0) << log << "FLOOR(perception) roll error " << s["roll_error_deg"] << " deg";
  // The floor holds where the floor or a tread beneath is in view.
  EXPECT_LE(num(s["height_error_beneath_visible_cm"]), 3.0)
      << log << "FLOOR(perception) height error " << s["height_error_beneath_visible_cm"] << " cm over "
      << s["height_frames_beneath_visible"] << " frames with the surface beneath in view";

  EXPECT_EQ(num(s["model_steps_detected"]), num(s["model_steps_real"]))
      << log << "FLOOR(tracker) model holds " << s["model_steps_detected"] << " of " << s["model_steps_real"]
      << " real steps";
  EXPECT_EQ(num(s["false_steps"]["model"]), 0) << log << "FLOOR(tracker) false steps in the model: "
                                               << s["false_steps"]["model"];
  if (stairs) {
    EXPECT_LE(num(s["riser_error_cm"]["mean_abs"]), 1.0)
        << log << "FLOOR(tracker) riser error " << s["riser_error_cm"] << " cm";
    EXPECT_LE(num(s["tread_error_cm"]["mean_abs"]), 1.0)
        << log << "FLOOR(tracker) tread error " << s["tread_error_cm"] << " cm";
  }
}


}  // namespace
