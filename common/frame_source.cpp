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
    ++i_;
    return true;
  }
  const std::optional<GroundTruth>& ground_truth() const override { return truth_; }
  double progress() const override { return seq_.size() ? double(i_) / seq_.size() : 1.0; }
  size_t size_hint() const override { return seq_.size(); }

 private:
  SequenceReader seq_;
  std::optional<GroundTruth> truth_;
  size_t i_ = 0, odom_i_ = 0;
};

// Ground truth may be logged before or after its depth frame; frames are
// matched to it by seq with one frame of look-ahead.
class LogSource : public FrameSource {
 public:
  LogSource(const std::string& path, std::string depth_channel, std::string truth_channel,
            std::string odometry_channel)
      : log_(path),
        depth_channel_(std::move(depth_channel)),
        truth_channel_(std::move(truth_channel)),
        odometry_channel_(std::move(odometry_channel)) {}

  bool next(SourceFrame& f) override {
    while (pending_.size() < 2 && !eof_) read_one();
    if (pending_.empty()) return false;
    f.image = std::move(pending_.front().first);
    f.odometry = std::move(pending_.front().second);
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
    std::string error;
    if (ev.channel == depth_channel_) {
      depth_frame_t msg;
      DepthImage img;
      if (decode_message(ev.data.data(), ev.data.size(), msg, error) && from_lcm(msg, img, error)) {
        pending_.emplace_back(std::move(img), std::move(odometry_));
        odometry_.clear();
        return;
      }
      ++invalid_;
      last_error_ = log_.path() + ": " + ev.channel + " message skipped: " + error;
    } else if (ev.channel == odometry_channel_) {
      pose_t msg;
      OdometrySample o;
      if (decode_message(ev.data.data(), ev.data.size(), msg, error) && from_lcm(msg, o, error)) {
        // At most one frame period of samples is held: a log of odometry
        // without depth cannot grow this without bound.
        if (odometry_.size() >= kMaxOdometryPerFrame) odometry_.erase(odometry_.begin());
        odometry_.push_back(o);
        return;
      }
      ++invalid_;
      last_error_ = log_.path() + ": " + ev.channel + " message skipped: " + error;
    } else if (ev.channel == truth_channel_) {
      ground_truth_t msg;
      GroundTruth gt;
      GroundTruthFrame fr;
      if (decode_message(ev.data.data(), ev.data.size(), msg, error) && from_lcm(msg, gt, fr, error)) {
        if (!truth_) truth_ = gt;
        truth_by_seq_[msg.seq] = fr;
        return;
      }
      ++invalid_;
      last_error_ = log_.path() + ": " + ev.channel + " message skipped: " + error;
    }
  }

  static constexpr size_t kMaxOdometryPerFrame = 1000;  // 1 kHz odometry, a 1 s gap between frames

  LogReader log_;
  std::string depth_channel_, truth_channel_, odometry_channel_;
  std::deque<std::pair<DepthImage, std::vector<OdometrySample>>> pending_;
  std::vector<OdometrySample> odometry_;  // since the last depth frame
  std::map<int32_t, GroundTruthFrame> truth_by_seq_;
  std::optional<GroundTruth> truth_;
  bool eof_ = false;
  size_t invalid_ = 0;
  std::string last_error_;
};

}  // namespace

std::unique_ptr<FrameSource> open_frame_source(const std::string& path, const std::string& depth_channel,
                                               const std::string& truth_channel, const std::string& odometry_channel) {
  if (std::filesystem::is_directory(path)) return std::make_unique<SequenceSource>(path);
  return std::make_unique<LogSource>(path, depth_channel, truth_channel, odometry_channel);
}

}  // namespace stairs
