#include "viewer/frame_history.hpp"

namespace stairs::viewer {

void FrameHistory::push(DepthImage img) {
  frames_.push_back(std::move(img));
  while (frames_.size() > capacity_) frames_.pop_front();
}

const DepthImage* FrameHistory::find(int64_t utime, int32_t seq) const {
  for (auto it = frames_.rbegin(); it != frames_.rend(); ++it)
    if (it->utime == utime && it->seq == seq) return &*it;
  return nullptr;
}

}  // namespace stairs::viewer
