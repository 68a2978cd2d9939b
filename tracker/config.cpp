#include "tracker/config.hpp"

#include "common/config_file.hpp"
#include "common/config_json.hpp"

#include <stdexcept>

namespace stairs {

void validate(const TrackerConfig& c) {
  ConfigChecker ranges("tracker");
  const_cast<TrackerConfig&>(c).visit(ranges);
  const auto require = [](bool ok, const char* key, const char* what) {
    if (!ok) throw std::runtime_error(std::string("'tracker.") + key + "' must be " + what);
  };
  require(c.registration.icp_min_distance_m <= c.registration.icp_max_distance_m, "registration.icp_min_distance_m",
          "at most registration.icp_max_distance_m");
  require(c.direction.majority <= c.direction.window, "direction.majority", "at most direction.window");
  require(c.motion.predict_camera_s <= c.motion.max_prediction_s, "motion.predict_camera_s",
          "at most motion.max_prediction_s");
  require(c.overhang.face_band_from < c.overhang.face_band_to &&
              c.overhang.face_band_to < 1 - c.overhang.top_band_fraction,
          "overhang.face_band_from", "below overhang.face_band_to, itself below 1 - overhang.top_band_fraction");
}

TrackerConfig tracker_config_from_json(const nlohmann::json& object, const std::string& file) {
  const TrackerConfig c = read_config<TrackerConfig>(
      object, file, "tracker",
      " (tracker keys are grouped by concept, e.g. 'tracker.lifecycle.reset_after_s': see config/default.json or "
      "--print-config)");
  try {
    validate(c);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(file + ": " + e.what());
  }
  return c;
}

TrackerConfig tracker_config_from_sections(const ConfigSections& sections, const std::string& file) {
  TrackerConfig c = tracker_config_from_json(sections.tracker, file);
  c.stair.landing_min_depth_m = stair_definition_from_json(sections.stair, file).landing_min_depth_m;
  c.mount = mount_from_json(sections.mount, file);
  return c;
}

TrackerConfig load_tracker_config(const std::string& path) {
  return tracker_config_from_sections(read_config_file(path), path);
}

StairDefinition stair_definition(const TrackerConfig& c) {
  return {c.stair.landing_min_depth_m};
}

nlohmann::ordered_json to_json(const TrackerConfig& c) { return config_to_json(c); }

}  // namespace stairs
