// libFuzzer target: decoding and validation of every message a daemon takes
// besides depth: observations and models (tracker, viewer), IMU samples and
// odometry poses (perception, tracker). The first byte picks the type; the rest
// is the message body, behind the type's fingerprint (fingerprint.hpp).
#include "common/lcm_bridge.hpp"
#include "tests/fuzz/fingerprint.hpp"

#include <cmath>
#include <cstdint>
#include <cstdlib>

namespace {

// Decodes body as T and converts it; a rejection must carry a reason, an
// accepted message must satisfy `usable`.
template <class T, class Value, class Usable>
void check(const uint8_t* body, size_t size, Usable usable) {
  const std::vector<uint8_t> bytes = stairs::fuzz::with_fingerprint<T>(body, size);
  T msg;
  Value value;
  std::string error;
  if (stairs::decode_message(bytes.data(), bytes.size(), msg, error) && stairs::from_lcm(msg, value, error)) {
    if (!usable(value)) std::abort();
  } else if (error.empty()) {
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const uint8_t* body = data + 1;
  const size_t n = size - 1;
  switch (data[0] % 4) {
    case 0:
      check<stairs::stair_observation_t, stairs::Observation>(body, n, [](const stairs::Observation& obs) {
        for (const stairs::Step& s : obs.steps)
          if (!s.nosing_m.allFinite() || s.riser_plane >= static_cast<int>(obs.planes.size())) return false;
        return true;
      });
      break;
    case 1:
      check<stairs::stair_model_t, stairs::StairModel>(
          body, n, [](const stairs::StairModel& m) { return m.camera_position_m.allFinite(); });
      break;
    case 2:
      check<stairs::imu_t, stairs::ImuSample>(body, n, [](const stairs::ImuSample& s) {
        return s.specific_force_mps2.allFinite() && s.angular_rate_radps.allFinite();
      });
      break;
    default:
      check<stairs::pose_t, stairs::OdometrySample>(body, n, [](const stairs::OdometrySample& o) {
        return o.position_m.allFinite() && std::abs(o.orientation.norm() - 1.0) < 1e-6;
      });
  }
  return 0;
}
