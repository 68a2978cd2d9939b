#include "common/frame_source.hpp"

#include "common/lcm_bridge.hpp"
#include "common/lcm_log.hpp"
#include "common/sequence.hpp"

#include <deque>
#include <filesystem>
#include <map>

namespace stairs {
namespace {

class SequenceSource : public FrameSource {
 public:
  explicit SequenceSource(const std::string& dir) : seq_(dir) {
    if (seq_.ground_truth()) {
      truth_ = seq_.ground_truth();
      truth_->frames.clear();
    }
  }
  bool next(SourceFrame& f) override {
    if (i_ >= seq_.size()) return false;
    f.image = seq_.read(i_);
    f.truth.reset();
    const auto& gt = seq_.ground_truth();
    if (gt && i_ < gt->frames.size()) f.truth = gt->frames[i_];
    f.odometry.clear();
    const auto& odometry = seq_.odometry();
    while (odom_i_ < odometry.size() && odometry[odom_i_].utime <= f.image.utime) f.odometry.push_back(odometry[odom_i_++]);
    f.imu.clear();
    f.imu_in_camera_frame = true;
    const auto& imu = seq_.imu();
    while (imu_i_ < imu.size() && imu[imu_i_].utime <= f.image.utime) f.imu.push_back(imu[imu_i_++]);
    ++i_;
    return true;
  }
  const std::optional<GroundTruth>& ground_truth() const override { return truth_; }
  double progress() const override { return seq_.size() ? double(i_) / seq_.size() : 1.0; }
  size_t size_hint() const override { return seq_.size(); }
  std::vector<std::string> warnings() const override { return seq_.warnings(); }

 private:
  SequenceReader seq_;
  std::optional<GroundTruth> truth_;
  size_t i_ = 0, odom_i_ = 0, imu_i_ = 0;
};

// Ground truth may be logged before or after its depth frame; frames are
// matched to it by seq with one frame of look-ahead.
class LogSource : public FrameSource {
 public:
  LogSource(const std::string& path, std::string depth_channel, std::string truth_channel,
            std::string odometry_channel, std::string imu_channel)
      : log_(path),
        depth_channel_(std::move(depth_channel)),
        truth_channel_(std::move(truth_channel)),
        odometry_channel_(std::move(odometry_channel)),
        imu_channel_(std::move(imu_channel)) {}

  bool next(SourceFrame& f) override {
    while (pending_.size() < 2 && !eof_) read_one();
    if (pending_.empty()) return false;
    f.image = std::move(pending_.front().image);
    f.odometry = std::move(pending_.front().odometry);
    f.imu = std::move(pending_.front().imu);
    f.imu_in_camera_frame = false;
    pending_.pop_front();
    f.truth.reset();
    if (auto it = truth_by_seq_.find(f.image.seq); it != truth_by_seq_.end()) {
      f.truth = it->second;
      truth_by_seq_.erase(truth_by_seq_.begin(), std::next(it));
    }
    return true;
  }
  const std::optional<GroundTruth>& ground_truth() const override { return truth_; }
  double progress() const override {
    return log_.file_size() ? double(log_.bytes_read()) / log_.file_size() : 1.0;
  }
  size_t size_hint() const override { return 0; }
  size_t invalid() const override { return invalid_; }
  std::string last_error() const override { return last_error_; }

 private:
  void read_one() {
    LogEvent ev;
    if (!log_.next(ev)) {
      eof_ = true;
      return;
    }
    if (ev.channel == depth_channel_) {
      DepthImage img;
      if (!decode<depth_frame_t>(ev, img)) return;
      pending_.push_back({std::move(img), std::move(odometry_), std::move(imu_)});
      odometry_.clear();
      imu_.clear();
    } else if (ev.channel == odometry_channel_) {
      OdometrySample o;
      if (decode<pose_t>(ev, o)) hold(odometry_, o);
    } else if (ev.channel == imu_channel_) {
      ImuSample sample;
      if (decode<imu_t>(ev, sample)) hold(imu_, sample);
    } else if (ev.channel == truth_channel_) {
      ground_truth_t msg;
      GroundTruth gt;
      GroundTruthFrame fr;
      std::string error;
      if (decode_message(ev.data.data(), ev.data.size(), msg, error) && from_lcm(msg, gt, fr, error)) {
        if (!truth_) truth_ = gt;
        truth_by_seq_[msg.seq] = fr;
      } else {
        skipped(ev, error);
      }
    }
  }

  // Decodes and validates one message into `out`; a bad one is counted and named.
  template <class Msg, class Value>
  bool decode(const LogEvent& ev, Value& out) {
    Msg msg;
    std::string error;
    if (decode_message(ev.data.data(), ev.data.size(), msg, error) && from_lcm(msg, out, error)) return true;
    skipped(ev, error);
    return false;
  }
  void skipped(const LogEvent& ev, const std::string& error) {
    ++invalid_;
    last_error_ = log_.path() + ": " + ev.channel + " message skipped: " + error;
  }
  template <class Sample>
  static void hold(std::vector<Sample>& held, const Sample& s) {
    if (held.size() >= kMaxSamplesPerFrame) held.erase(held.begin());
    held.push_back(s);
  }

  // Odometry or IMU samples held per frame (1 kHz over a 1 s gap between frames):
  // a log of them without depth cannot grow this without bound; the oldest go.
  static constexpr size_t kMaxSamplesPerFrame = 1000;
  struct Pending {
    DepthImage image;
    std::vector<OdometrySample> odometry;
    std::vector<ImuSample> imu;
  };

  LogReader log_;
  std::string depth_channel_, truth_channel_, odometry_channel_, imu_channel_;
  std::deque<Pending> pending_;
  std::vector<OdometrySample> odometry_;  // since the last depth frame
  std::vector<ImuSample> imu_;
  std::map<int32_t, GroundTruthFrame> truth_by_seq_;
  std::optional<GroundTruth> truth_;
  bool eof_ = false;
  size_t invalid_ = 0;
  std::string last_error_;
};

}  // namespace

std::unique_ptr<FrameSource> open_frame_source(const std::string& path, const std::string& depth_channel,
                                               const std::string& truth_channel, const std::string& odometry_channel,
                                               const std::string& imu_channel) {
  if (std::filesystem::is_directory(path)) return std::make_unique<SequenceSource>(path);
  return std::make_unique<LogSource>(path, depth_channel, truth_channel, odometry_channel, imu_channel);
}

}  // namespace stairs
