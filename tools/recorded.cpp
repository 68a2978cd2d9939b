#include "tools/recorded.hpp"

#include "common/frame_source.hpp"
#include "common/lcm_bridge.hpp"
#include "common/lcm_log.hpp"
#include "tools/progress.hpp"
#include "tools/replay.hpp"
#include "tracker/model_output.hpp"

#include <deque>
#include <map>
#include <stdexcept>

namespace stairs::eval {
namespace {

// What the live chain published for one depth frame: only what the scores
// read, so a long field recording does not keep every plane in memory.
struct Answer {
  std::optional<FrameResult> observation;  // camera, direction, steps, status, latency
  std::optional<std::vector<Step>> tracked_steps;
  std::optional<TrackedCamera> tracked_camera;
  double tracker_ms = 0.0;
};

// Answers keyed by the depth frame's utime; a log replayed twice into one
// recording repeats utimes, so each key holds a queue in recording order.
using Answers = std::map<int64_t, std::deque<Answer>>;

Answer& answer_for(Answers& answers, int64_t source_utime, bool model) {
  std::deque<Answer>& q = answers[source_utime];
  // A model follows its observation: it joins the newest answer still without one.
  if (model && !q.empty() && !q.back().tracked_steps) return q.back();
  if (!model && !q.empty() && !q.back().observation && q.back().tracked_steps) return q.back();
  return q.emplace_back();
}

FrameResult observation_result(const Observation& obs) {
  FrameResult f;
  f.camera = obs.camera;
  f.direction = obs.direction;
  f.steps = obs.steps;
  f.status = obs.status;
  f.latency.push_back({"perception", obs.latency_ms});
  for (const StageLatency& s : obs.stages) f.latency.push_back({"perception/" + s.name, s.ms});
  return f;
}

// Decodes one recorded message as Msg and hands it with its value to `use`;
// one that fails to decode or validate counts as rejected.
template <class Msg, class Value, class Use>
void take(const LogEvent& ev, int& accepted, int& rejected, Use use) {
  Msg msg;
  Value value;
  std::string error;
  if (!decode_and_convert(ev.data.data(), ev.data.size(), msg, value, error)) {
    ++rejected;
    return;
  }
  ++accepted;
  use(msg, value);
}

// Pass one: the observations and models of the whole log, and the last model.
Answers read_answers(const std::string& path, const RecordedOptions& o, RecordedCounts& counts,
                     std::optional<StairModel>& last_model) {
  Answers answers;
  LogReader log(path);
  LogEvent ev;
  while (log.next(ev)) {
    if (ev.channel == o.channels.observation) {
      take<stair_observation_t, Observation>(ev, counts.observations, counts.rejected_messages,
                                             [&](const stair_observation_t& msg, Observation& obs) {
                                               answer_for(answers, msg.source_utime, false).observation =
                                                   observation_result(obs);
                                             });
    } else if (ev.channel == o.channels.model) {
      take<stair_model_t, StairModel>(ev, counts.models, counts.rejected_messages,
                                      [&](const stair_model_t& msg, StairModel& model) {
                                        Answer& a = answer_for(answers, msg.source_utime, true);
                                        a.tracked_steps = steps_from_camera(model);
                                        a.tracked_camera = tracked_camera_of(model);
                                        a.tracker_ms = model.update_latency_ms;
                                        model.planes.clear();  // the report and the JSON hold steps only
                                        last_model = std::move(model);
                                      });
    }
  }
  return answers;
}

}  // namespace

RunResult score_recorded(const std::string& path, const RecordedOptions& options) {
  RunResult r;
  r.input = path;
  r.recorded.emplace();
  RecordedCounts& counts = *r.recorded;
  Answers answers = read_answers(path, options, counts, r.model);
  if (counts.observations == 0)
    throw std::runtime_error(path + ": no valid message on " + options.channels.observation +
                             ": nothing the live chain published was recorded (drop --recorded to run perception)");

  auto source = open_frame_source(path, options.channels.depth, options.channels.truth);
  ProgressBar bar(options.progress);
  SourceFrame sf;
  while (source->next(sf)) {
    ++r.frames_total;
    if (options.max_frames > 0 && r.frames_processed >= options.max_frames) continue;
    FrameResult f;
    std::deque<Answer>* q = nullptr;
    if (auto it = answers.find(sf.image.utime); it != answers.end() && !it->second.empty()) q = &it->second;
    if (q && q->front().observation) {
      f = std::move(*q->front().observation);
    } else {
      ++counts.frames_without_observation;
      f.status = "no observation recorded for this frame (dropped by the live chain)";
    }
    if (q && q->front().tracked_steps) {
      f.tracked_steps = std::move(q->front().tracked_steps);
      f.tracked_camera = std::move(q->front().tracked_camera);
      f.latency.push_back({"tracker", q->front().tracker_ms});
    } else {
      if (q && q->front().observation) ++counts.frames_without_model;
      f.tracked_steps.emplace();  // the robot knew no steps around its camera for this frame
      f.tracked_camera.emplace();
    }
    if (q) q->pop_front();
    f.timestamp_s = sf.truth ? sf.truth->timestamp : sf.image.utime * 1e-6;
    f.truth = std::move(sf.truth);
    f.K = sf.image.K;
    r.frames.push_back(std::move(f));
    ++r.frames_processed;
    bar.update(source->progress(), r.frames_processed);
  }
  r.frames_invalid = static_cast<int>(source->invalid());
  if (r.frames_processed == 0)
    throw std::runtime_error(path + ": no valid depth frames on " + options.channels.depth +
                             " (a recorded run is scored against the frames it was given)");
  if (source->ground_truth())
    r.score = score_run(r.frames, r.model ? &r.model->flights : nullptr, *source->ground_truth());
  return r;
}

}  // namespace stairs::eval
