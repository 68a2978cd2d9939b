// DESIGN.md's Result JSON (the output of stairs-eval --json): every key always
// present, null where unknown.
#pragma once

#include "tools/score.hpp"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace stairs::eval {

// What a recorded live run held (stairs-eval --recorded).
struct RecordedCounts {
  int observations = 0;                // valid observations on the observation channel
  int models = 0;                      // valid models on the model channel
  int rejected_messages = 0;           // observations or models that failed to decode or validate
  int frames_without_observation = 0;  // depth frames the live chain never answered (scored as missed)
  int frames_without_model = 0;        // depth frames with an observation but no model
};

struct RunResult {
  std::string input;
  int frames_total = 0;      // frames the input holds (valid ones)
  int frames_processed = 0;  // frames run through the pipeline
  int frames_invalid = 0;    // depth messages the source rejected
  std::vector<FrameResult> frames;
  std::optional<StairModel> model;  // absent when no tracker ran
  std::optional<Score> score;       // present with ground truth
  std::optional<RecordedCounts> recorded;  // present when the daemons' recorded output was scored
};

const char* direction_name(Direction d);  // "up", "down", "none"

nlohmann::json frame_to_json(const FrameResult& f);
nlohmann::json model_to_json(const StairModel& m);
nlohmann::json score_to_json(const Score& s);
nlohmann::json recorded_to_json(const RecordedCounts& c);
nlohmann::json result_to_json(const RunResult& r);

}  // namespace stairs::eval
