// Fixed-rate sensor samples along a trajectory (the simulated IMU and odometry).
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

namespace stairs::sim {

// The samples from `next` (advanced) up to trajectory time t_s inclusive:
// sample k is measure(k / rate_hz), stamped utime0 + its time in us.
template <class Measure>
auto samples_until(int& next, double rate_hz, double t_s, int64_t utime0, Measure measure) {
  std::vector<decltype(measure(0.0))> out;
  for (; next / rate_hz <= t_s + 1e-9; ++next) {
    const double t = next / rate_hz;
    auto s = measure(t);
    s.utime = utime0 + std::llround(t * 1e6);
    out.push_back(s);
  }
  return out;
}

}  // namespace stairs::sim
