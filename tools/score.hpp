// Scores of a replayed run against ground truth: DESIGN.md 'Scores' made exact
// (the thesis' tables 6.1-6.4). Free functions over common/types.hpp.
#pragma once

#include "common/mount.hpp"
#include "common/types.hpp"

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace stairs::eval {

// The tracker's camera after a frame (DESIGN.md frames[].tracked_camera).
struct TrackedCamera {
  bool valid = false;
  // Above the surface beneath and the model step beneath it (counted across
  // flights, -1 = floor before the first): none where the model has not seen
  // what lies beneath the camera.
  std::optional<double> height_m;
  std::optional<int> step_index;
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();  // camera centre in the model's stair frame
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // optical -> model stair frame
  std::optional<double> position_uncertainty_m;  // how far off position_m may be along the stair
};

// What the replay keeps of one frame.
struct FrameResult {
  double timestamp_s = 0.0;
  CameraPose camera;
  Direction direction = Direction::None;
  std::vector<Step> steps;  // nearest first, gravity-aligned camera frame
  std::string status;       // perception's status (why no staircase, what verification dropped)
  // The tracker's model steps relative to its camera after this frame (same
  // frame; tracker/model_output.hpp steps_from_camera), absent when no tracker
  // ran; empty while the model has no camera.
  std::optional<std::vector<Step>> tracked_steps;
  std::optional<TrackedCamera> tracked_camera;  // absent when no tracker ran
  // The tracker's robot base (the same fields for the base frame, orientation base -> stair),
  // present when the tracker ran with a mount (DESIGN.md frames[].tracked_base, this project's).
  std::optional<TrackedCamera> tracked_base;
  // "perception", "tracker" and perception's own stages as "perception/<name>".
  std::vector<StageLatency> latency;
  std::optional<GroundTruthFrame> truth;
  std::optional<Intrinsics> K;  // of the processed frame: what the camera could see
};

struct ErrorStats {
  int n = 0;
  std::optional<double> mean_signed;  // estimate - truth
  std::optional<double> mean_abs;
};

struct LatencyStats {
  int n = 0;
  double median_ms = 0.0;
  double p95_ms = 0.0;  // nearest rank
};

// One frame's share of Table 6.1, for per-frame diagnosis (Result JSON
// frames[].score): real step indices, bottom first across flights.
struct FrameScore {
  std::vector<int> visible;                 // DESIGN.md's visible_steps
  std::vector<int> nosing_in_view;          // visible ones whose nosing projects into the image
  std::vector<int> matched;                 // real step per detected step, -1 when false
  std::optional<std::vector<int>> tracked;  // the same for the tracked steps
  double pitch_deg = 0, roll_deg = 0, height_m = 0;  // the true camera pose
  int true_step_index = -1;  // real step beneath the camera (-1 = floor before the first)
  // The tracked camera's step beneath as a real step index, through this
  // frame's tracked-step matches; absent without a valid tracked camera or
  // when none of its steps matched.
  std::optional<int> tracked_step_index;
  std::optional<double> tracked_position_error_cm;  // along the stair (x), with that offset
  // With a mount: the real step beneath the true base, and the tracked base's as a real index.
  std::optional<int> true_base_step_index, tracked_base_step_index;
};

struct Score {
  // Per processed frame, aligned with the run's frames; nullopt without truth.
  std::vector<std::optional<FrameScore>> frames;
  // Table 6.1: over the frames with ground truth.
  int frames_scored = 0;
  int visible_steps = 0;
  int frame_steps_matched = 0;  // matches to visible real steps
  std::optional<double> frame_step_detection;  // matched / visible, 0..1
  // The same over the visible steps whose nosing's centre projects into the
  // image (nosing_in_view): a landing seen after its edge has passed beneath
  // the camera, or a tread whose front edge is below the view, is visible by
  // DESIGN.md's pixel count but offers no edge to detect.
  int visible_steps_nosing_in_view = 0;
  int frame_steps_matched_nosing_in_view = 0;
  std::optional<double> frame_step_detection_nosing_in_view;
  int frame_false_steps = 0;  // detections matched to no real step, all frames
  int frames_with_false_steps = 0;
  // Table 6.1 over the tracker's steps relative to the camera (FrameResult::
  // tracked_steps) instead of perception's: what the whole system knows of the
  // visible steps on each frame. Same denominator (visible_steps); a frame
  // without tracked steps matches none. Absent when no tracker ran.
  bool tracked_scored = false;  // some frame had tracked steps (a tracker ran)
  int tracked_steps_matched = 0;
  std::optional<double> frame_step_detection_tracked;
  int tracked_false_steps = 0;  // tracked steps matched to no real step, all frames
  // The tracker's camera (TrackedCamera) against the true one, over the frames
  // where it is valid: its model is put on the real steps by the whole-step
  // offset most of this frame's tracked-step matches agree on.
  int tracked_camera_frames = 0;                   // valid tracked camera, with truth
  int tracked_beneath_frames = 0;                  // ... and a known step beneath
  std::optional<double> tracked_camera_coverage;   // those / frames from the first of them on
  ErrorStats tracked_height_error_cm;              // above the surface beneath
  std::optional<double> tracked_step_index_accuracy;  // right step beneath / tracked_beneath_frames
  ErrorStats tracked_position_error_cm;            // along the stair (x), where an offset is known
  // The tracker's robot base against the true one (the true camera carried back through the
  // mount), over the frames where it is valid, as for the camera.
  int tracked_base_frames = 0;
  int tracked_base_beneath_frames = 0;
  ErrorStats tracked_base_height_error_cm;             // base origin above the surface beneath
  std::optional<double> tracked_base_step_index_accuracy;  // right step beneath the base / beneath frames
  // Tables 6.2-6.4: the final model (absent when no tracker ran).
  bool model_scored = false;
  int model_steps_real = 0;
  int model_steps_detected = 0;
  int model_false_steps = 0;
  int model_step_offset = 0;  // model origin sits on this real step's riser
  ErrorStats riser_error_cm;
  ErrorStats tread_error_cm;  // landing depths excluded
  // Camera pose: mean absolute over frames with a valid estimated pose.
  int pose_frames_valid = 0;
  ErrorStats pitch_error_deg;
  ErrorStats roll_error_deg;
  ErrorStats height_error_cm;  // only where both heights are known
  // The same over the frames where the surface beneath the camera shows in the
  // image (beneath_in_view): elsewhere no single frame can tell its height.
  ErrorStats height_error_beneath_visible_cm;
  std::map<std::string, LatencyStats> latency_ms;
};

struct StepMatch {
  int detected = -1;
  int real = -1;  // index into real_steps()
};

// All real steps, bottom first across flights (the indexing of visible_steps).
std::vector<Step> real_steps(const GroundTruth& truth);

// Gravity-aligned camera frame -> stair frame, from the TRUE camera pose:
// origin at the camera centre, x = horizontal projection of the optical axis,
// z up, y = z x x.
Eigen::Isometry3d gravity_frame_in_stair(const GroundTruthFrame& frame);

// A real step's nosing line (stair y axis through (x, 0, z)) in the
// gravity-aligned frame, evaluated at lateral coordinate `left_m`; where the
// line runs within 30 deg of the optical axis, at its point nearest the camera.
Eigen::Vector3d true_nosing_in_gravity_frame(const Step& real, const GroundTruthFrame& frame,
                                             double left_m = 0.0);

// The real step beneath the true camera: the highest whose nosing is behind
// it (-1 = the floor before the first step).
int true_step_beneath(const GroundTruthFrame& frame, const std::vector<Step>& real);
// The same beneath a point at x along the stair.
int true_step_at(double x_m, const std::vector<Step>& real);

// True when part of the level the camera stands over (floor, tread or
// landing, from the real steps) lies in the image: the lowest image row, seen
// at the true pitch (roll ignored), meets that level before it ends ahead
// (at the next riser going up, at its own nosing going down) by at least
// 5 cm. Needs the frame's intrinsics.
bool beneath_in_view(const GroundTruthFrame& frame, const std::vector<Step>& real, const Intrinsics& K);

// True when the centre of the real step's nosing (stair frame (x, 0, z))
// projects into the image of the true camera (occlusion not considered).
bool nosing_in_view(const GroundTruthFrame& frame, const Step& real, const Intrinsics& K);

// One frame: detected nosings matched to real ones (|dx| <= tread/2 and
// |dz| <= riser/2 of the real step), nearest pair first, each side at most once.
std::vector<StepMatch> match_frame_steps(const std::vector<Step>& detected,
                                         const std::vector<Step>& real,
                                         const GroundTruthFrame& frame);

struct ModelMatch {
  int offset_steps = 0;
  std::vector<StepMatch> matches;
};

// The final model against the truth, both in stair frames: the model is shifted
// by whole real steps (offset o puts the model origin at real step o's riser
// foot; negative o extrapolates with step 0) and the offset matching most steps
// wins (then the one agreeing most on landings, then the smaller summed squared
// distance, then the smaller |o|).
ModelMatch match_model_steps(const std::vector<Step>& model, const std::vector<Step>& real);

// Median and nearest-rank p95 of a sample.
LatencyStats latency_stats(std::vector<double> samples_ms);
// Per stage name over all frames (no ground truth needed).
std::map<std::string, LatencyStats> latency_by_stage(const std::vector<FrameResult>& frames);

// Everything above over a run. `model` holds the final model's flights, or is
// null when no tracker ran; `mount` is the one the tracker was given (its base is
// scored against the true camera carried back through it; none: not scored).
Score score_run(const std::vector<FrameResult>& frames, const std::vector<Flight>* model,
                const GroundTruth& truth, const MountConfig& mount = {});

}  // namespace stairs::eval
