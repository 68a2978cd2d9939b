#include "viewer/view_state.hpp"

#include "common/lcm_bridge.hpp"

namespace stairs::viewer {

ViewState::ViewState(Channels channels, size_t depth_history)
    : channels_(std::move(channels)), history_(depth_history), max_truth_frames_(depth_history) {}

namespace {
template <class Msg, class Value>
bool decode(const void* data, size_t size, Value& value, std::string& error) {
  Msg msg;
  return decode_message(data, size, msg, error) && from_lcm(msg, value, error);
}
}  // namespace

MessageKind ViewState::handle(const std::string& channel, const void* data, size_t size, std::string& error) {
  if (channel == channels_.depth) {
    DepthImage img;
    if (!decode<depth_frame_t>(data, size, img, error)) return MessageKind::Unknown;
    history_.push(std::move(img));
    return MessageKind::Depth;
  }
  if (channel == channels_.observation) {
    Observation obs;
    if (!decode<stair_observation_t>(data, size, obs, error)) return MessageKind::Unknown;
    observation_ = std::move(obs);
    return MessageKind::Observation;
  }
  if (channel == channels_.model) {
    StairModel model;
    if (!decode<stair_model_t>(data, size, model, error)) return MessageKind::Unknown;
    model_ = std::move(model);
    return MessageKind::Model;
  }
  if (channel == channels_.truth) {
    ground_truth_t msg;
    GroundTruth gt;
    GroundTruthFrame frame;
    if (!decode_message(data, size, msg, error) || !from_lcm(msg, gt, frame, error)) return MessageKind::Unknown;
    truth_ = std::move(gt);
    truth_frames_[msg.seq] = frame;
    while (truth_frames_.size() > max_truth_frames_) truth_frames_.erase(truth_frames_.begin());
    return MessageKind::Truth;
  }
  return MessageKind::Unknown;
}

ViewInput ViewState::view(ImageMode mode, const ViewStats& stats) const {
  ViewInput in;
  in.mode = mode;
  in.stats = stats;
  in.observation = observation_ ? &*observation_ : nullptr;
  in.model = model_ ? &*model_ : nullptr;
  in.truth = truth_ ? &*truth_ : nullptr;
  in.depth = observation_ ? history_.find(observation_->source_utime, observation_->source_seq) : nullptr;
  if (!in.depth) in.depth = history_.latest();
  if (in.depth)
    if (auto it = truth_frames_.find(in.depth->seq); it != truth_frames_.end()) in.truth_frame = &it->second;
  return in;
}

}  // namespace stairs::viewer
