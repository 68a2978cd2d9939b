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
    ++i_;
    return true;
  }
  const std::optional<GroundTruth>& ground_truth() const override { return truth_; }
  double progress() const override { return seq_.size() ? double(i_) / seq_.size() : 1.0; }
  size_t size_hint() const override { return seq_.size(); }

 private:
  SequenceReader seq_;
  std::optional<GroundTruth> truth_;
  size_t i_ = 0;
};

// Ground truth may be logged before or after its depth frame; frames are
// matched to it by seq with one frame of look-ahead.
class LogSource : public FrameSource {
 public:
  LogSource(const std::string& path, std::string depth_channel, std::string truth_channel)
      : log_(path), depth_channel_(std::move(depth_channel)), truth_channel_(std::move(truth_channel)) {}

  bool next(SourceFrame& f) override {
    while (pending_.size() < 2 && !eof_) read_one();
    if (pending_.empty()) return false;
    f.image = std::move(pending_.front());
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
        pending_.push_back(std::move(img));
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

  LogReader log_;
  std::string depth_channel_, truth_channel_;
  std::deque<DepthImage> pending_;
  std::map<int32_t, GroundTruthFrame> truth_by_seq_;
  std::optional<GroundTruth> truth_;
  bool eof_ = false;
  size_t invalid_ = 0;
  std::string last_error_;
};

}  // namespace

std::unique_ptr<FrameSource> open_frame_source(const std::string& path, const std::string& depth_channel,
                                               const std::string& truth_channel) {
  if (std::filesystem::is_directory(path)) return std::make_unique<SequenceSource>(path);
  return std::make_unique<LogSource>(path, depth_channel, truth_channel);
}

}  // namespace stairs
