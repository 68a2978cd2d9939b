// The perception pipeline: one depth frame in, one stair observation out
// (gravity-aligned camera frame: x forward, y left, z up, camera centre origin).
#pragma once

#include "common/types.hpp"
#include "perception/config.hpp"
#include "perception/normals.hpp"

#include <optional>
#include <vector>

namespace stairs {

class Pipeline {
 public:
  explicit Pipeline(PerceptionConfig cfg = {});
  // Never throws on bad input: an unusable frame gives camera.valid = false,
  // direction None and a status naming the reason. Frames of one stream come
  // in order: the previous frame's up (within gravity_prior_max_gap_s) is the
  // gravity prior.
  Observation process(const DepthImage& frame);
  const PerceptionConfig& config() const { return cfg_; }

 private:
  PerceptionConfig cfg_;
  NormalGrid grid_;          // reused buffers
  std::vector<int> labels_;  // reused buffers
  std::optional<Eigen::Vector3f> up_prior_;  // optical frame, of the frame at prior_utime_
  int64_t prior_utime_ = 0;
};

}  // namespace stairs
