#include "perception/config.hpp"

#include "common/config_file.hpp"
#include "common/config_json.hpp"

#include <stdexcept>

namespace stairs {
namespace {

// What one key's range cannot say: values that must agree with each other.
void check_consistency(const PerceptionConfig& c, const std::string& file) {
  const auto require = [&](bool ok, const char* key, const char* what) {
    if (!ok) throw std::runtime_error(file + ": 'perception." + key + "' must be " + what);
  };
  require(c.normals.min_depth_m < c.normals.max_depth_m, "normals.min_depth_m", "below normals.max_depth_m");
  require(c.region_growing.distance_m <= c.region_growing.max_distance_m, "region_growing.distance_m",
          "at most region_growing.max_distance_m");
  require(c.edges_normal_image.canny_low <= c.edges_normal_image.canny_high, "edges_normal_image.canny_low",
          "at most edges_normal_image.canny_high");
  require(c.stair.riser_min_m <= c.stair.riser_max_m, "stair.riser_min_m", "at most stair.riser_max_m");
  require(c.stair.tread_min_m <= c.stair.tread_max_m, "stair.tread_min_m", "at most stair.tread_max_m");
  require(c.stair.step_rule_min_m <= c.stair.step_rule_max_m, "stair.step_rule_min_m",
          "at most stair.step_rule_max_m");
  const VerificationConfig& v = c.verification;
  require(v.rise_outlier_m >= v.rise_tolerance_m, "verification.rise_outlier_m",
          "at least verification.rise_tolerance_m");
  require(v.end_probes_through <= v.end_probes, "verification.end_probes_through", "at most verification.end_probes");
  require(v.run_outlier_m >= v.run_tolerance_m, "verification.run_outlier_m", "at least verification.run_tolerance_m");
  require(c.imu.plane_agreement_deg <= c.imu.max_disagreement_deg, "imu.plane_agreement_deg",
          "at most imu.max_disagreement_deg");
}

}  // namespace

PerceptionConfig perception_config_from_json(const nlohmann::json& object, const std::string& file) {
  const PerceptionConfig c = read_config<PerceptionConfig>(
      object, file, "perception",
      " (perception keys are grouped by stage, e.g. 'perception.stair.riser_min_m': see config/default.json or "
      "--print-config)");
  check_consistency(c, file);
  return c;
}

PerceptionConfig perception_config_from_sections(const ConfigSections& sections, const std::string& file) {
  PerceptionConfig c = perception_config_from_json(sections.perception, file);
  c.stair.landing_min_depth_m = static_cast<float>(stair_definition_from_json(sections.stair, file).landing_min_depth_m);
  c.mount = mount_from_json(sections.mount, file);
  return c;
}

PerceptionConfig load_perception_config(const std::string& path) {
  return perception_config_from_sections(read_config_file(path), path);
}

StairDefinition stair_definition(const PerceptionConfig& c) { return {c.stair.landing_min_depth_m}; }

nlohmann::ordered_json to_json(const PerceptionConfig& c) { return config_to_json(c); }

}  // namespace stairs
