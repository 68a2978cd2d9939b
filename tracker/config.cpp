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
  require(c.icp_min_distance_m <= c.icp_max_distance_m, "icp_min_distance_m", "at most icp_max_distance_m");
  require(c.direction_majority <= c.direction_window, "direction_majority", "at most direction_window");
  require(c.predict_camera_s <= c.max_prediction_s, "predict_camera_s", "at most max_prediction_s");
}

TrackerConfig tracker_config_from_json(const nlohmann::json& object, const std::string& file) {
  TrackerConfig c;
  ConfigReader r(object, file, "tracker");
  c.visit(r);
  r.finish();
  try {
    validate(c);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(file + ": " + e.what());
  }
  return c;
}

TrackerConfig load_tracker_config(const std::string& path) {
  return tracker_config_from_json(read_config_file(path).tracker, path);
}

nlohmann::ordered_json to_json(const TrackerConfig& c) { return config_to_json(c); }

}  // namespace stairs
