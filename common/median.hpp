// The median of a non-empty set: the upper one of an even count (an element of the set, no mean).
// One definition for the perception and tracker libraries.
#pragma once

#include <algorithm>
#include <vector>

namespace stairs {

// In place, reordering `v` (a caller's scratch buffer keeps its capacity).
template <class T>
T median_in_place(std::vector<T>& v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

template <class T>
T median(std::vector<T> v) {
  return median_in_place(v);
}

}  // namespace stairs
