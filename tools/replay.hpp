// Replays a log or sequence directory through perception and the tracker
// in-process, frame by frame, as fast as possible (no transport in the loop).
#pragma once

#include "chain/config.hpp"
#include "tools/result_json.hpp"

#include <functional>
#include <string>

namespace stairs::eval {

struct ReplayOptions {
  int max_frames = 0;         // frames to process, 0 = all
  int width = 0, height = 0;  // downsample to this resolution, 0 = native
  bool progress = false;      // progress bar on stderr
  ChainConfig config;         // perception and tracker parameters (chain/config.hpp)
};

// Called with every frame as the pipeline will see it, before it runs, outside
// the timed section (stairs-bench times its peer here).
using FrameHook = std::function<void(const DepthImage&)>;

// What a model says about its camera, as the Result JSON's tracked_camera:
// height and step only where the model knows what is beneath.
TrackedCamera tracked_camera_of(const StairModel& model);
// The same for the robot base (stair_model_t base_*), the orientation base -> stair.
TrackedCamera tracked_base_of(const StairModel& model);

// Throws std::runtime_error naming the file on a bad input or config.
RunResult replay(const std::string& input, const ReplayOptions& options, const FrameHook& hook = {});

}  // namespace stairs::eval
