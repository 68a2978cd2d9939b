#include "tools/replay.hpp"

#include "chain/offline_chain.hpp"
#include "common/frame_source.hpp"
#include "tools/downsample.hpp"
#include "tools/progress.hpp"
#include "tracker/model_output.hpp"

#include <cstdio>
#include <stdexcept>

namespace stairs::eval {

namespace {

// A pose of the model as the Result JSON gives it: height and step only where the model knows
// what is beneath, the height only where it also knows it (camera_height_known).
TrackedCamera tracked(bool valid, bool beneath_known, bool height_known, double height_m, int step_index,
                      const Eigen::Vector3d& position_m, const Eigen::Quaterniond& orientation,
                      double position_uncertainty_m) {
  TrackedCamera c;
  c.valid = valid;
  if (position_uncertainty_m >= 0.0) c.position_uncertainty_m = position_uncertainty_m;
  if (beneath_known) c.step_index = step_index;
  if (beneath_known && height_known) c.height_m = height_m;
  c.position_m = position_m;
  c.orientation = orientation;
  return c;
}

}  // namespace

TrackedCamera tracked_camera_of(const StairModel& m) {
  return tracked(m.camera_valid, m.camera_beneath_known, m.camera_height_known, m.camera_height_m, m.camera_step_index,
                 m.camera_position_m, m.camera_orientation, m.camera_position_uncertainty_m);
}

TrackedCamera tracked_base_of(const StairModel& m) {
  return tracked(m.base_valid, m.base_beneath_known, m.base_height_known, m.base_height_m, m.base_step_index,
                 m.base_position_m, m.base_orientation, m.base_valid ? m.camera_position_uncertainty_m : -1.0);
}

RunResult replay(const std::string& input, const ReplayOptions& options, const FrameHook& hook) {
  auto source = open_frame_source(input);
  for (const std::string& w : source->warnings()) std::fprintf(stderr, "warning: %s\n", w.c_str());
  OfflineChain chain(options.config);
  ProgressBar bar(options.progress);

  RunResult r;
  r.input = input;
  int factor = 0;
  SourceFrame sf;
  while (source->next(sf)) {
    ++r.frames_total;
    if (options.max_frames > 0 && r.frames_processed >= options.max_frames) continue;
    if (factor == 0)
      factor = options.width > 0 ? downsample_factor(sf.image.K, options.width, options.height) : 1;
    const DepthImage image = downsample(sf.image, factor);
    if (hook) hook(image);
    chain.add_inputs(sf);
    ChainStep step = chain.process(image);

    FrameResult f;
    f.timestamp_s = sf.truth ? sf.truth->timestamp : image.utime * 1e-6;
    f.camera = step.observation.camera;
    f.direction = step.observation.direction;
    f.steps = std::move(step.observation.steps);
    f.status = step.observation.status;
    f.tracked_steps = steps_from_camera(*step.model);
    f.tracked_camera = tracked_camera_of(*step.model);
    if (options.config.tracker.mount.configured()) f.tracked_base = tracked_base_of(*step.model);
    f.latency.push_back({"perception", step.perception_ms});
    f.latency.push_back({"tracker", step.tracker_ms});
    for (const StageLatency& s : step.observation.stages) f.latency.push_back({"perception/" + s.name, s.ms});
    f.truth = std::move(sf.truth);
    f.K = image.K;
    r.frames.push_back(std::move(f));
    ++r.frames_processed;
    bar.update(source->progress(), r.frames_processed);
  }
  r.frames_invalid = static_cast<int>(source->invalid());
  if (r.frames_processed == 0)
    throw std::runtime_error(input + ": no valid depth frames" +
                             (source->last_error().empty() ? "" : " (" + source->last_error() + ")"));
  r.model = chain.model();
  r.model->planes.clear();  // the report and the JSON hold steps only
  if (source->ground_truth()) r.score = score_run(r.frames, &r.model->flights, *source->ground_truth(), options.config.tracker.mount);
  return r;
}

}  // namespace stairs::eval
