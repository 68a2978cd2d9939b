#include "tools/result_json.hpp"

#include "fixtures.hpp"

#include <gtest/gtest.h>

namespace stairs::eval {
namespace {

using nlohmann::json;
using namespace test;

void expect_keys(const json& j, std::initializer_list<const char*> keys, const std::string& where) {
  ASSERT_TRUE(j.is_object()) << where << " is not an object: " << j.dump();
  for (const char* k : keys) EXPECT_TRUE(j.contains(k)) << where << " lacks '" << k << "'";
}

void expect_step(const json& s, const std::string& where) {
  expect_keys(s, {"riser_height_m", "tread_depth_m", "width_m", "landing", "nosing_m"}, where);
  ASSERT_TRUE(s["nosing_m"].is_array()) << where;
  EXPECT_EQ(s["nosing_m"].size(), 2u) << where;
}

RunResult unknowns() {
  RunResult r;
  r.input = "some.lcmlog";
  r.frames_total = 2;
  r.frames_processed = 1;
  FrameResult f;
  f.timestamp_s = 0.033;
  Step s;
  s.riser_height_m = 0.18;  // tread unseen
  f.steps.push_back(s);
  f.latency = {{"perception", 7.0}};  // tracker did not run
  r.frames.push_back(f);
  return r;
}

TEST(EvalResultJson, EveryDesignKeyPresentNullWhereUnknown) {
  const json j = result_to_json(unknowns());
  expect_keys(j, {"input", "frames_total", "frames_processed", "frames", "model", "score"}, "result");
  EXPECT_EQ(j["input"], "some.lcmlog");
  EXPECT_EQ(j["frames_total"], 2);
  EXPECT_EQ(j["frames_processed"], 1);
  EXPECT_TRUE(j["model"].is_null());
  EXPECT_TRUE(j["score"].is_null());
  ASSERT_EQ(j["frames"].size(), 1u);
  const json& f = j["frames"][0];
  expect_keys(f, {"timestamp", "camera", "direction", "steps", "latency_ms"}, "frame");
  EXPECT_DOUBLE_EQ(f["timestamp"].get<double>(), 0.033);
  expect_keys(f["camera"], {"valid", "pitch_deg", "roll_deg", "height_m", "distance_m"}, "camera");
  EXPECT_EQ(f["camera"]["valid"], false);
  for (const char* k : {"pitch_deg", "roll_deg", "height_m", "distance_m"})
    EXPECT_TRUE(f["camera"][k].is_null()) << k;
  EXPECT_EQ(f["direction"], "none");
  expect_step(f["steps"][0], "frame step");
  EXPECT_TRUE(f["steps"][0]["tread_depth_m"].is_null());
  expect_keys(f["latency_ms"], {"perception", "tracker"}, "latency_ms");
  EXPECT_TRUE(f["latency_ms"]["tracker"].is_null());
  EXPECT_TRUE(f["tracked_steps"].is_null()) << "no tracker ran";
}

TEST(EvalResultJson, ModelAndScoreKeys) {
  RunResult r = unknowns();
  r.frames[0].camera.valid = true;
  r.frames[0].camera.pitch_deg = -35.0;
  r.frames[0].camera.height_m = 1.0;
  r.frames[0].direction = Direction::Up;
  r.frames[0].truth = camera_frame(-1.5, 0.0, 1.0, -35.0);
  const GroundTruth truth = straight_stair();
  r.frames[0].tracked_steps = perfect_detections(truth, *r.frames[0].truth);
  StairModel m;
  m.direction = Direction::Up;
  m.flights = truth.flights;
  r.model = m;
  r.score = score_run(r.frames, &m.flights, truth);
  const json j = result_to_json(r);

  const json& f = j["frames"][0];
  EXPECT_EQ(f["camera"]["pitch_deg"], -35.0);
  EXPECT_EQ(f["camera"]["height_m"], 1.0);
  EXPECT_TRUE(f["camera"]["distance_m"].is_null());
  EXPECT_EQ(f["direction"], "up");
  ASSERT_EQ(f["tracked_steps"].size(), size_t(kSteps));
  for (const json& s : f["tracked_steps"]) expect_step(s, "tracked step");

  expect_keys(j["model"], {"direction", "flights"}, "model");
  EXPECT_EQ(j["model"]["direction"], "up");
  ASSERT_EQ(j["model"]["flights"].size(), 1u);
  ASSERT_EQ(j["model"]["flights"][0]["steps"].size(), size_t(kSteps));
  for (const json& s : j["model"]["flights"][0]["steps"]) expect_step(s, "model step");
  EXPECT_EQ(j["model"]["flights"][0]["steps"][kSteps - 1]["landing"], true);

  const json& s = j["score"];
  expect_keys(s, {"frame_step_detection", "model_steps_detected", "model_steps_real", "riser_error_cm",
                  "tread_error_cm", "false_steps", "pitch_error_deg", "roll_error_deg", "height_error_cm",
                  "height_error_beneath_visible_cm", "height_frames_beneath_visible", "latency_ms"},
              "score");
  EXPECT_EQ(s["model_steps_detected"], kSteps);
  EXPECT_EQ(s["model_steps_real"], kSteps);
  expect_keys(s["riser_error_cm"], {"mean_signed", "mean_abs"}, "riser_error_cm");
  expect_keys(s["tread_error_cm"], {"mean_signed", "mean_abs"}, "tread_error_cm");
  expect_keys(s["false_steps"], {"frames", "per_frame", "model"}, "false_steps");
  EXPECT_EQ(s["false_steps"]["model"], 0);
  // One frame, one detection that is no real nosing: a false step, 0 of 5 seen.
  EXPECT_EQ(s["false_steps"]["frames"], 1);
  EXPECT_EQ(s["frame_step_detection"], 0.0);
  EXPECT_EQ(s["frame_step_detection_tracked"], 1.0);
  EXPECT_EQ(s["frame_steps_matched_tracked"], kSteps);
  EXPECT_EQ(s["false_steps"]["frames_tracked"], 0);
  EXPECT_EQ(s["pitch_error_deg"], 0.0);
  EXPECT_TRUE(s["roll_error_deg"].is_number());
  expect_keys(s["latency_ms"]["perception"], {"median", "p95"}, "latency_ms.perception");
}

TEST(EvalResultJson, ScoreWithoutModelHasNulls) {
  RunResult r = unknowns();
  r.frames[0].truth = camera_frame(-1.5, 0.0, 1.0, -35.0);
  r.score = score_run(r.frames, nullptr, straight_stair());
  const json s = result_to_json(r)["score"];
  for (const char* k : {"model_steps_detected", "model_steps_real", "riser_error_cm", "tread_error_cm"})
    EXPECT_TRUE(s[k].is_null()) << k;
  EXPECT_TRUE(s["false_steps"]["model"].is_null());
  EXPECT_TRUE(s["frame_step_detection_tracked"].is_null());
  EXPECT_TRUE(s["false_steps"]["frames_tracked"].is_null());
  EXPECT_TRUE(s["pitch_error_deg"].is_null());  // no valid pose
}

}  // namespace
}  // namespace stairs::eval
