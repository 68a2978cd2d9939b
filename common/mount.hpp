// Where the camera sits on its carrier: the config file's top-level "mount"
// object. A property of the robot, not of one stage: perception's camera
// height reads it (issue 15, "the mount"); absent (height 0) for a hand-held
// camera.
#pragma once

#include "common/config_json.hpp"

#include <string>

namespace stairs {

struct MountConfig {
  float height_m = 0.0f;   // m; camera above the ground the carrier stands on; 0 = no mount (hand-held)
  float pitch_deg = 0.0f;  // deg; camera pitch with the carrier on level ground (DESIGN.md: below horizon < 0)
  float roll_deg = 0.0f;   // deg; camera roll with the carrier on level ground

  bool configured() const { return height_m > 0.0f; }

  template <class V>
  void visit(V& v) {
    v("height_m", height_m, 0.0f, 10.0f);
    v("pitch_deg", pitch_deg, -90.0f, 90.0f);
    v("roll_deg", roll_deg, -180.0f, 180.0f);
  }
};

// The "mount" object of a config (any subset of its keys); errors name `file` and the key.
inline MountConfig mount_from_json(const nlohmann::json& object, const std::string& file) {
  return read_config<MountConfig>(object, file, "mount",
                                  " (the top-level 'mount' object: height_m, pitch_deg, roll_deg of the camera on "
                                  "its robot; see config/stairs-sim-robot.json)");
}

}  // namespace stairs
