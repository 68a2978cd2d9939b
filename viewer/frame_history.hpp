// The last few depth frames, so an observation (which arrives later) is drawn
// over the very frame it was made from.
#pragma once

#include "common/types.hpp"

#include <deque>

namespace stairs::viewer {

class FrameHistory {
 public:
  explicit FrameHistory(size_t capacity) : capacity_(capacity > 0 ? capacity : 1) {}
  void push(DepthImage img);
  // The frame with this utime and seq, or null.
  const DepthImage* find(int64_t utime, int32_t seq) const;
  const DepthImage* latest() const { return frames_.empty() ? nullptr : &frames_.back(); }
  size_t size() const { return frames_.size(); }

 private:
  size_t capacity_;
  std::deque<DepthImage> frames_;
};

}  // namespace stairs::viewer
