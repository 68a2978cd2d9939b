// libFuzzer target: observation and model decoding and validation.
#include "common/lcm_bridge.hpp"

#include <cmath>
#include <cstdint>
#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string error;
  stairs::stair_observation_t obs_msg;
  stairs::Observation obs;
  if (stairs::decode_message(data, size, obs_msg, error) && stairs::from_lcm(obs_msg, obs, error)) {
    for (const stairs::Step& s : obs.steps)
      if (!s.nosing_m.allFinite() || s.riser_plane >= static_cast<int>(obs.planes.size())) std::abort();
  }
  stairs::stair_model_t model_msg;
  stairs::StairModel model;
  if (stairs::decode_message(data, size, model_msg, error) && stairs::from_lcm(model_msg, model, error)) {
    if (!model.camera_position_m.allFinite()) std::abort();
  }
  return 0;
}
