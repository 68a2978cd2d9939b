// A small, portable random generator (splitmix64): the same seed gives the
// same numbers on every platform and standard library, which std::normal_distribution
// does not promise.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

namespace stairs::sim {

class Rng {
 public:
  explicit Rng(uint64_t seed) : state_(seed) {}
  uint64_t next() {
    uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)
  double gaussian() {  // Box-Muller, the second value kept for the next call
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    const double u1 = 1.0 - uniform(), u2 = uniform();
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare_ = r * std::sin(2.0 * M_PI * u2);
    has_spare_ = true;
    return r * std::cos(2.0 * M_PI * u2);
  }

 private:
  uint64_t state_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

// Seed of one frame from the run's seed and the frame's sequence number.
inline uint64_t frame_seed(uint64_t seed, int32_t seq) {
  Rng r(seed ^ (0xd1b54a32d192ed03ULL * static_cast<uint64_t>(static_cast<uint32_t>(seq) + 1)));
  return r.next();
}

}  // namespace stairs::sim

namespace stairs::sim {

// Standard normal samples drawn from a fixed table of 2^16 Box-Muller values,
// 16 random bits each: a quarter of a generator call per sample instead of a
// log, a sqrt and a sincos, which the per-pixel noise cannot afford at 30 Hz.
class FastNormal {
 public:
  explicit FastNormal(Rng& rng) : rng_(rng) {}
  float operator()() {
    if (left_ == 0) {
      bits_ = rng_.next();
      left_ = 4;
    }
    const float v = table()[bits_ & 0xffff];
    bits_ >>= 16;
    --left_;
    return v;
  }

 private:
  static const std::vector<float>& table() {
    static const std::vector<float> t = [] {
      std::vector<float> out(1 << 16);
      Rng r(0x5eed);
      for (float& v : out) v = static_cast<float>(r.gaussian());
      return out;
    }();
    return t;
  }
  Rng& rng_;
  uint64_t bits_ = 0;
  int left_ = 0;
};

}  // namespace stairs::sim
