// Frames from an LCM log or a sequence directory, for the offline tools
// (stairs-eval, stairs-viewer --render).
#pragma once

#include "common/types.hpp"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace stairs {

struct SourceFrame {
  DepthImage image;
  std::optional<GroundTruthFrame> truth;
  // Odometry that arrived since the previous frame (a sequence: timestamps up
  // to this frame's), in order; empty without odometry.
  std::vector<OdometrySample> odometry;
  // IMU samples likewise; a sequence's imu.txt is in the camera optical frame,
  // a log's STAIRS_IMU in the IMU's own (perception's imu_to_camera turns it).
  std::vector<ImuSample> imu;
  bool imu_in_camera_frame = true;
};

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  // Next frame; false at the end. Throws std::runtime_error naming the file on
  // a truncated log or a broken sequence directory.
  virtual bool next(SourceFrame& frame) = 0;
  // The stair's ground truth (flights), once known.
  virtual const std::optional<GroundTruth>& ground_truth() const = 0;
  virtual double progress() const = 0;  // 0..1
  virtual size_t size_hint() const = 0;  // frames, 0 if unknown
  // Depth messages skipped because they failed validation, with the last reason.
  virtual size_t invalid() const { return 0; }
  virtual std::string last_error() const { return {}; }
  // Optional inputs left out, each "FILE[:LINE]: reason".
  virtual std::vector<std::string> warnings() const { return {}; }
};

// A directory is read as a sequence, a file as an LCM log.
std::unique_ptr<FrameSource> open_frame_source(const std::string& path,
                                               const std::string& depth_channel = "STAIRS_DEPTH",
                                               const std::string& truth_channel = "STAIRS_GROUND_TRUTH",
                                               const std::string& odometry_channel = "STAIRS_ODOMETRY",
                                               const std::string& imu_channel = "STAIRS_IMU");

}  // namespace stairs
