// libFuzzer target: depth frame decoding and validation, as a daemon sees them.
// The input is the message body; the fingerprint is prepended (fingerprint.hpp),
// and the raw input is also tried so a wrong fingerprint is rejected cleanly.
#include "common/lcm_bridge.hpp"
#include "tests/fuzz/fingerprint.hpp"

#include <cstdint>
#include <cstdlib>

namespace {

void check(const uint8_t* data, size_t size) {
  stairs::depth_frame_t msg;
  stairs::DepthImage img;
  std::string error;
  if (stairs::decode_message(data, size, msg, error) && stairs::from_lcm(msg, img, error)) {
    // A frame that passes validation must be fully usable.
    if (img.depth.size() != static_cast<size_t>(img.K.width) * img.K.height) std::abort();
  } else if (error.empty()) {
    std::abort();  // every rejection carries a reason
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  check(data, size);
  const std::vector<uint8_t> msg = stairs::fuzz::with_fingerprint<stairs::depth_frame_t>(data, size);
  check(msg.data(), msg.size());
  return 0;
}
