// Up/down direction with hysteresis over the last n observations (thesis 5.2):
// a single misjudged frame never flips the model's direction.
#pragma once

#include "common/types.hpp"

#include <deque>

namespace stairs {

class DirectionFilter {
 public:
  DirectionFilter(int window, int majority) : window_(window), majority_(majority) {}
  Direction update(Direction observed);
  Direction current() const { return current_; }
  void reset();

 private:
  int window_, majority_;
  std::deque<Direction> recent_;
  Direction current_ = Direction::None;
};

}  // namespace stairs
