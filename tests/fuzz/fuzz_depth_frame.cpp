// libFuzzer target: depth frame decoding and validation, as a daemon sees them.
#include "common/lcm_bridge.hpp"

#include <cstdint>
#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  stairs::depth_frame_t msg;
  stairs::DepthImage img;
  std::string error;
  if (stairs::decode_message(data, size, msg, error) && stairs::from_lcm(msg, img, error)) {
    // A frame that passes validation must be fully usable.
    if (img.depth.size() != static_cast<size_t>(img.K.width) * img.K.height) std::abort();
  } else if (error.empty()) {
    std::abort();  // every rejection carries a reason
  }
  return 0;
}
