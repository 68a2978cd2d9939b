// Sequence directories (DESIGN.md): camera.json, depth.txt, depth/*.png (16-bit),
// optional groundtruth.json. Input of every offline tool, output of stairs-sim.
#pragma once

#include "common/types.hpp"

#include <optional>
#include <string>
#include <vector>

namespace stairs {

class SequenceReader {
 public:
  // Reads camera.json, depth.txt and groundtruth.json (if present). Throws
  // std::runtime_error "FILE: reason" on a missing or malformed file. The
  // optional odometry.txt and imu.txt are left out when malformed, with a
  // warning "FILE:LINE: reason" (warnings()): the depth is still usable.
  explicit SequenceReader(const std::string& dir);

  size_t size() const { return entries_.size(); }
  const Intrinsics& intrinsics() const { return K_; }
  double depth_scale() const { return depth_scale_; }
  double timestamp(size_t i) const { return entries_.at(i).timestamp; }
  const std::string& depth_path(size_t i) const { return entries_.at(i).path; }
  const std::optional<GroundTruth>& ground_truth() const { return ground_truth_; }
  // odometry.txt (optional, empty without it), in time order: utime = timestamp in us.
  const std::vector<OdometrySample>& odometry() const { return odometry_; }
  // imu.txt (optional, empty without it), in time order, camera optical frame.
  const std::vector<ImuSample>& imu() const { return imu_; }
  const std::vector<std::string>& warnings() const { return warnings_; }

  // Loads frame i; utime = timestamp in us, seq = i. Throws "FILE: reason" on a
  // missing, unreadable, 8-bit or wrongly sized PNG.
  DepthImage read(size_t i) const;

 private:
  struct Entry {
    double timestamp;
    std::string path;
  };
  std::string dir_;
  Intrinsics K_;
  double depth_scale_ = 0.001;
  std::vector<Entry> entries_;
  std::optional<GroundTruth> ground_truth_;
  std::vector<OdometrySample> odometry_;
  std::vector<ImuSample> imu_;
  std::vector<std::string> warnings_;
};

// imu.txt: "# timestamp_s ax ay az gx gy gz", one sample per line. Throws
// "FILE:LINE: reason" on a malformed line or time going backwards.
std::vector<ImuSample> read_imu_file(const std::string& path);

// odometry.txt: "# timestamp_s x y z qw qx qy qz", one pose per line. Throws
// "FILE:LINE: reason" on a malformed line, a non-unit quaternion or time
// going backwards.
std::vector<OdometrySample> read_odometry_file(const std::string& path);

class SequenceWriter {
 public:
  // Creates dir/ and dir/depth/. camera.json and depth.txt are written by
  // finish(), so an interrupted run leaves a directory no reader accepts.
  SequenceWriter(const std::string& dir, const Intrinsics& K, double depth_scale);

  // Writes depth/NNNNNN.png for the image (which must match K).
  void write(const DepthImage& img, double timestamp_s);
  // Appends one line to odometry.txt (written by finish()); utime in us.
  void write_odometry(const OdometrySample& o);
  // Appends one line to imu.txt (written by finish()); camera optical frame.
  void write_imu(const ImuSample& s);
  void finish(const std::optional<GroundTruth>& ground_truth = std::nullopt);

 private:
  std::string dir_;
  Intrinsics K_;
  double depth_scale_;
  std::string index_;
  std::string odometry_, imu_;
  size_t count_ = 0;
};

}  // namespace stairs
