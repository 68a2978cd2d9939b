#include "chain/offline_chain.hpp"

#include "perception/imu_gravity.hpp"

#include <chrono>

namespace stairs {
namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

OfflineChain::OfflineChain(const ChainConfig& config)
    : config_(config),
      pipeline_(config.perception),
      tracker_(config.tracker),
      imu_to_camera_(imu_to_camera(config.perception.imu)) {}

void OfflineChain::add_inputs(const SourceFrame& frame) {
  for (const OdometrySample& o : frame.odometry) tracker_.add_odometry(o);
  for (const ImuSample& s : frame.imu) pipeline_.add_imu(frame.imu_in_camera_frame ? s : turned(s, imu_to_camera_));
}

ChainStep OfflineChain::process(const DepthImage& image) {
  ChainStep step;
  const auto t0 = std::chrono::steady_clock::now();
  step.observation = pipeline_.process(image);
  step.perception_ms = ms_since(t0);
  const auto t1 = std::chrono::steady_clock::now();
  step.model = &tracker_.update(step.observation);
  step.tracker_ms = ms_since(t1);
  return step;
}

}  // namespace stairs
