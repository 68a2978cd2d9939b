// What perception and the tracker both take a stair to be: the config file's
// top-level "stair" object, read once and handed to both (one value, not two
// copies that can disagree).
#pragma once

#include "common/config_json.hpp"

#include <string>

namespace stairs {

struct StairDefinition {
  double landing_min_depth_m = 0.5;  // m; a deeper tread is a landing (DIN 18065 treads are 0.23-0.37 m)

  template <class V>
  void visit(V& v) {
    v("landing_min_depth_m", landing_min_depth_m, 0.0, 10.0);
  }
};

// The "stair" object of a config (any subset of its keys); errors name `file` and the key.
inline StairDefinition stair_definition_from_json(const nlohmann::json& object, const std::string& file) {
  return read_config<StairDefinition>(object, file, "stair",
                                      " (the top-level 'stair' object holds what perception and the tracker "
                                      "share: see config/default.json)");
}

}  // namespace stairs
