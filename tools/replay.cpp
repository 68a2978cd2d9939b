#include "tools/replay.hpp"

#include "common/frame_source.hpp"
#include "common/json_io.hpp"
#include "perception/config.hpp"
#include "perception/imu_gravity.hpp"
#include "perception/pipeline.hpp"
#include "tools/downsample.hpp"
#include "tools/progress.hpp"
#include "tracker/config.hpp"
#include "tracker/model_output.hpp"
#include "tracker/tracker.hpp"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace stairs::eval {
namespace {

using Clock = std::chrono::steady_clock;

double ms_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// The loaders take a file, so each section of the combined config goes through
// its own temporary file.
template <typename Config, typename Loader>
Config load_section(const nlohmann::json& all, const char* key, const std::string& path, Loader load) {
  auto it = all.find(key);
  if (it == all.end() || it->is_null()) return Config{};
  if (!it->is_object()) throw std::runtime_error(path + ": '" + key + "' is not an object");
  const std::string tmp = (std::filesystem::temp_directory_path() /
                           ("stairs-eval-" + std::to_string(getpid()) + "-" + key + ".json"))
                              .string();
  write_json_file(tmp, *it);
  try {
    Config c = load(tmp);
    std::filesystem::remove(tmp);
    return c;
  } catch (const std::exception& e) {
    std::filesystem::remove(tmp);
    throw std::runtime_error(path + ": '" + key + "': " + e.what());
  }
}


}  // namespace

TrackedCamera tracked_camera_of(const StairModel& m) {
  TrackedCamera c;
  c.valid = m.camera_valid;
  if (m.camera_beneath_known) {
    c.height_m = m.camera_height_m;
    c.step_index = m.camera_step_index;
  }
  c.position_m = m.camera_position_m;
  c.orientation = m.camera_orientation;
  return c;
}


RunResult replay(const std::string& input, const ReplayOptions& options, const FrameHook& hook) {
  PerceptionConfig perception_config;
  TrackerConfig tracker_config;
  if (!options.config_path.empty()) {
    const nlohmann::json all = read_json_file(options.config_path);
    if (!all.is_object()) throw std::runtime_error(options.config_path + ": not a JSON object");
    perception_config = load_section<PerceptionConfig>(all, "perception", options.config_path,
                                                                    load_perception_config);
    tracker_config = load_section<TrackerConfig>(all, "tracker", options.config_path, load_tracker_config);
  }
  auto source = open_frame_source(input);
  for (const std::string& w : source->warnings()) std::fprintf(stderr, "warning: %s\n", w.c_str());
  Pipeline pipeline(perception_config);
  const Eigen::Matrix3d imu_rotation = imu_to_camera(perception_config.imu);
  Tracker tracker(tracker_config);
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

    for (const OdometrySample& o : sf.odometry) tracker.add_odometry(o);
    for (const ImuSample& s : sf.imu) pipeline.add_imu(sf.imu_in_camera_frame ? s : turned(s, imu_rotation));
    const auto t0 = Clock::now();
    Observation obs = pipeline.process(image);
    const auto t1 = Clock::now();
    tracker.update(obs);
    const auto t2 = Clock::now();

    FrameResult f;
    f.timestamp_s = sf.truth ? sf.truth->timestamp : image.utime * 1e-6;
    f.camera = obs.camera;
    f.direction = obs.direction;
    f.steps = std::move(obs.steps);
    f.status = obs.status;
    f.tracked_steps = steps_from_camera(tracker.model());
    f.tracked_camera = tracked_camera_of(tracker.model());
    f.latency.push_back({"perception", ms_between(t0, t1)});
    f.latency.push_back({"tracker", ms_between(t1, t2)});
    for (const StageLatency& s : obs.stages) f.latency.push_back({"perception/" + s.name, s.ms});
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
  r.model = tracker.model();
  r.model->planes.clear();  // the report and the JSON hold steps only
  if (source->ground_truth()) r.score = score_run(r.frames, &r.model->flights, *source->ground_truth());
  return r;
}

}  // namespace stairs::eval
