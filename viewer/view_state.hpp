// What the viewer knows from the messages it received (live or from a log):
// the last depth frames, the latest observation, model and ground truth.
#pragma once

#include "common/channels.hpp"
#include "common/types.hpp"
#include "viewer/frame_history.hpp"
#include "viewer/layout.hpp"

#include <map>
#include <optional>
#include <string>

namespace stairs::viewer {

using Channels = ChainChannels;

enum class MessageKind { Unknown, Depth, Observation, Model, Truth };

class ViewState {
 public:
  ViewState(Channels channels, size_t depth_history);
  // Decodes and validates one message (size caps, fingerprint, contents) and
  // keeps it. Unknown channels are ignored; an invalid message leaves the state
  // unchanged and sets `error`.
  MessageKind handle(const std::string& channel, const void* data, size_t size, std::string& error);

  // The view: the observation over the depth frame it was made from when that
  // frame is still kept (else the latest frame), the truth of that frame.
  ViewInput view(ImageMode mode, const ViewStats& stats) const;

  const std::optional<Observation>& observation() const { return observation_; }
  const std::optional<StairModel>& model() const { return model_; }
  const FrameHistory& history() const { return history_; }

 private:
  Channels channels_;
  FrameHistory history_;
  std::optional<Observation> observation_;
  std::optional<StairModel> model_;
  std::optional<GroundTruth> truth_;
  std::map<int32_t, GroundTruthFrame> truth_frames_;  // by depth seq, at most depth_history
  size_t max_truth_frames_;
};

}  // namespace stairs::viewer
