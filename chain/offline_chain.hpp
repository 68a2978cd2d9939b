// Perception and the tracker composed in-process, frame by frame, as the
// daemons compose them over LCM (thesis chapters 3-5): the one offline system
// behind stairs-eval, stairs-bench, stairs-viewer --render and the log tests.
#pragma once

#include "chain/config.hpp"
#include "common/frame_source.hpp"
#include "perception/pipeline.hpp"
#include "tracker/tracker.hpp"

#include <Eigen/Core>

namespace stairs {

struct ChainStep {
  Observation observation;   // perception's, for this frame
  const StairModel* model;   // the tracker's after it (owned by the chain)
  double perception_ms = 0.0, tracker_ms = 0.0;  // wall time of each
};

class OfflineChain {
 public:
  explicit OfflineChain(const ChainConfig& config = {});

  // The IMU samples and odometry that arrived with a frame (before process()):
  // a log's IMU is in the IMU's frame and turned by perception.imu.to_camera_*.
  void add_inputs(const SourceFrame& frame);
  // Perception, then the tracker, on one depth frame.
  ChainStep process(const DepthImage& image);

  const StairModel& model() const { return tracker_.model(); }
  const Tracker& tracker() const { return tracker_; }
  const ChainConfig& config() const { return config_; }

 private:
  ChainConfig config_;
  Pipeline pipeline_;
  Tracker tracker_;
  Eigen::Matrix3d imu_to_camera_;
};

}  // namespace stairs
