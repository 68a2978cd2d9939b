#include "tools/result_json.hpp"

#include "common/json_io.hpp"

namespace stairs::eval {
namespace {

using nlohmann::json;

template <typename T>
json or_null(const std::optional<T>& v) {
  return v ? json(*v) : json(nullptr);
}

json error_to_json(const ErrorStats& e) {
  return {{"mean_signed", or_null(e.mean_signed)}, {"mean_abs", or_null(e.mean_abs)}, {"n", e.n}};
}

json steps_to_json(const std::vector<Step>& steps) {
  json out = json::array();
  for (const Step& s : steps) out.push_back(step_to_json(s));
  return out;
}

}  // namespace

const char* direction_name(Direction d) {
  switch (d) {
    case Direction::Up: return "up";
    case Direction::Down: return "down";
    default: return "none";
  }
}

json tracked_camera_to_json(const TrackedCamera& c) {
  if (!c.valid) return {{"valid", false}, {"height_m", nullptr}, {"step_index", nullptr}, {"position_m", nullptr},
                        {"position_uncertainty_m", nullptr}, {"quaternion_wxyz", nullptr}};
  const Eigen::Quaterniond& q = c.orientation;
  return {{"valid", true},
          {"height_m", or_null(c.height_m)},
          {"step_index", or_null(c.step_index)},
          {"position_m", {c.position_m.x(), c.position_m.y(), c.position_m.z()}},
          {"position_uncertainty_m", or_null(c.position_uncertainty_m)},
          {"quaternion_wxyz", {q.w(), q.x(), q.y(), q.z()}}};
}

json frame_to_json(const FrameResult& f) {
  const CameraPose& c = f.camera;
  json camera = {{"valid", c.valid},
                 {"pitch_deg", c.valid ? json(c.pitch_deg) : json(nullptr)},
                 {"roll_deg", c.valid ? json(c.roll_deg) : json(nullptr)},
                 {"height_m", c.valid ? or_null(c.height_m) : json(nullptr)},
                 {"distance_m", c.valid ? or_null(c.distance_m) : json(nullptr)}};
  json latency = {{"perception", nullptr}, {"tracker", nullptr}};
  for (const StageLatency& l : f.latency) latency[l.name] = l.ms;
  json out = {{"timestamp", f.timestamp_s},
          {"camera", camera},
          {"direction", direction_name(f.direction)},
          {"steps", steps_to_json(f.steps)},
          {"tracked_steps", f.tracked_steps ? steps_to_json(*f.tracked_steps) : json(nullptr)},
          {"latency_ms", latency},
          {"status", f.status}};
  if (f.tracked_camera) out["tracked_camera"] = tracked_camera_to_json(*f.tracked_camera);
  if (f.tracked_base) out["tracked_base"] = tracked_camera_to_json(*f.tracked_base);
  return out;
}

json model_to_json(const StairModel& m) {
  json flights = json::array();
  for (const Flight& f : m.flights) flights.push_back({{"steps", steps_to_json(f.steps)}, {"width_m", f.width_m}});
  return {{"direction", direction_name(m.direction)}, {"flights", flights}};
}

json score_to_json(const Score& s) {
  const auto model_int = [&](int v) { return s.model_scored ? json(v) : json(nullptr); };
  json latency = json::object();
  for (const auto& [name, l] : s.latency_ms)
    latency[name] = {{"median", l.median_ms}, {"p95", l.p95_ms}, {"n", l.n}};
  return {
      {"frames_scored", s.frames_scored},
      {"frame_step_detection", or_null(s.frame_step_detection)},
      {"frame_steps_matched", s.frame_steps_matched},
      {"visible_steps", s.visible_steps},
      {"frame_step_detection_nosing_in_view", or_null(s.frame_step_detection_nosing_in_view)},
      {"visible_steps_nosing_in_view", s.visible_steps_nosing_in_view},
      {"frame_step_detection_tracked", or_null(s.frame_step_detection_tracked)},
      {"frame_steps_matched_tracked", s.tracked_scored ? json(s.tracked_steps_matched) : json(nullptr)},
      {"model_steps_detected", model_int(s.model_steps_detected)},
      {"model_steps_real", model_int(s.model_steps_real)},
      {"model_step_offset", model_int(s.model_step_offset)},
      {"riser_error_cm", s.model_scored ? error_to_json(s.riser_error_cm) : json(nullptr)},
      {"tread_error_cm", s.model_scored ? error_to_json(s.tread_error_cm) : json(nullptr)},
      {"false_steps",
       {{"frames", s.frame_false_steps},
        {"frames_with_false", s.frames_with_false_steps},
        {"per_frame", s.frames_scored ? json(double(s.frame_false_steps) / s.frames_scored) : json(nullptr)},
        {"model", model_int(s.model_false_steps)},
        {"frames_tracked", s.tracked_scored ? json(s.tracked_false_steps) : json(nullptr)}}},
      {"pose_frames_valid", s.pose_frames_valid},
      {"pitch_error_deg", or_null(s.pitch_error_deg.mean_abs)},
      {"roll_error_deg", or_null(s.roll_error_deg.mean_abs)},
      {"height_error_cm", or_null(s.height_error_cm.mean_abs)},
      {"height_frames", s.height_error_cm.n},
      {"height_error_beneath_visible_cm", or_null(s.height_error_beneath_visible_cm.mean_abs)},
      {"height_frames_beneath_visible", s.height_error_beneath_visible_cm.n},
      {"tracked_camera_frames", s.tracked_camera_frames},
      {"tracked_beneath_frames", s.tracked_beneath_frames},
      {"tracked_camera_coverage", or_null(s.tracked_camera_coverage)},
      {"tracked_height_error_cm", or_null(s.tracked_height_error_cm.mean_abs)},
      {"tracked_step_index_accuracy", or_null(s.tracked_step_index_accuracy)},
      {"tracked_position_error_cm", or_null(s.tracked_position_error_cm.mean_abs)},
      {"tracked_base_frames", s.tracked_base_frames},
      {"tracked_base_height_error_cm", or_null(s.tracked_base_height_error_cm.mean_abs)},
      {"tracked_base_step_index_accuracy", or_null(s.tracked_base_step_index_accuracy)},
      {"latency_ms", latency}};
}

// An extra key (a project extension, docs/DESIGN.md): what a recorded live run held.
json recorded_to_json(const RecordedCounts& c) {
  return {{"observations", c.observations},
          {"models", c.models},
          {"rejected_messages", c.rejected_messages},
          {"frames_without_observation", c.frames_without_observation},
          {"frames_without_model", c.frames_without_model}};
}

json result_to_json(const RunResult& r) {
  json frames = json::array();
  for (size_t i = 0; i < r.frames.size(); ++i) {
    json frame = frame_to_json(r.frames[i]);
    // An extra key (DESIGN.md lets readers ignore it): what this frame scored.
    if (r.score && i < r.score->frames.size() && r.score->frames[i]) {
      const FrameScore& fs = *r.score->frames[i];
      frame["score"] = {{"visible_steps", fs.visible},
                        {"nosing_in_view", fs.nosing_in_view},
                        {"matched", fs.matched},
                        {"tracked_matched", fs.tracked ? json(*fs.tracked) : json(nullptr)},
                        {"true_pitch_deg", fs.pitch_deg},
                        {"true_roll_deg", fs.roll_deg},
                        {"true_height_m", fs.height_m},
                        {"true_step_index", fs.true_step_index},
                        {"tracked_step_index", or_null(fs.tracked_step_index)},
                        {"tracked_position_error_cm", or_null(fs.tracked_position_error_cm)}};
      if (fs.true_base_step_index) {
        frame["score"]["true_base_step_index"] = *fs.true_base_step_index;
        frame["score"]["tracked_base_step_index"] = or_null(fs.tracked_base_step_index);
      }
    }
    frames.push_back(std::move(frame));
  }
  return {{"input", r.input},
          {"frames_total", r.frames_total},
          {"frames_processed", r.frames_processed},
          {"frames_invalid", r.frames_invalid},
          {"frames", frames},
          {"model", r.model ? model_to_json(*r.model) : json(nullptr)},
          {"score", r.score ? score_to_json(*r.score) : json(nullptr)},
          {"recorded", r.recorded ? recorded_to_json(*r.recorded) : json(nullptr)}};
}

}  // namespace stairs::eval
