#include "tracker/direction.hpp"

#include <algorithm>

namespace stairs {

Direction DirectionFilter::update(Direction observed) {
  recent_.push_back(observed);
  while (static_cast<int>(recent_.size()) > window_) recent_.pop_front();
  for (Direction d : {Direction::Up, Direction::Down})
    if (d != current_ && std::count(recent_.begin(), recent_.end(), d) >= majority_) current_ = d;
  // The first decided observation sets the direction of an undecided model.
  if (current_ == Direction::None && observed != Direction::None) current_ = observed;
  return current_;
}

void DirectionFilter::reset() {
  recent_.clear();
  current_ = Direction::None;
}

}  // namespace stairs
