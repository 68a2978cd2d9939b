#include "perception/config.hpp"

#include <nlohmann/json.hpp>

#include <fstream>
#include <stdexcept>

namespace stairs {

namespace {

template <class T>
void read_field(const nlohmann::json& value, const std::string& path, const std::string& key, T& field) {
  const bool ok = std::is_same<T, bool>::value ? value.is_boolean()
                  : std::is_integral<T>::value ? value.is_number_integer()
                                               : value.is_number();
  if (!ok) throw std::runtime_error(path + ": key '" + key + "' has the wrong type");
  field = value.get<T>();
}

// A config section: a JSON object whose keys read_key knows (it returns false
// for an unknown one); errors name the key as "<section>.<key>".
template <class ReadKey>
void read_section(const nlohmann::json& value, const std::string& path, const std::string& section,
                  ReadKey read_key) {
  if (!value.is_object()) throw std::runtime_error(path + ": key '" + section + "' must be an object");
  for (const auto& [key, v] : value.items())
    if (!read_key(key, v, section + "." + key))
      throw std::runtime_error(path + ": unknown perception config key '" + section + "." + key + "'");
}

}  // namespace

PerceptionConfig load_perception_config(const std::string& json_path) {
  std::ifstream in(json_path);
  if (!in) throw std::runtime_error(json_path + ": cannot open perception config");
  nlohmann::json j;
  try {
    in >> j;
  } catch (const std::exception& e) {
    throw std::runtime_error(json_path + ": invalid JSON: " + e.what());
  }
  if (!j.is_object()) throw std::runtime_error(json_path + ": perception config must be a JSON object");
  PerceptionConfig c;
#define STAIRS_PERCEPTION_FIELDS(X)                                                                      \
  X(grid_cell_px) X(normal_radius_cells) X(max_depth_m) X(min_depth_m) X(jump_ratio) X(cell_min_valid_fraction) X(cell_valid_fraction_range_m) X(inverse_depth_kink_per_m) X(smooth_normals)   \
  X(grow_angle_deg) X(grow_region_angle_deg) X(grow_distance_m) X(grow_max_distance_m) X(min_plane_px_320) X(max_tilt_from_image_up_deg) X(parallel_deg) X(gravity_prior_max_deg) X(gravity_prior_max_gap_s) X(gravity_min_support_fraction) \
  X(beneath_view_edge_margin_m) X(beneath_view_edge_tolerance) X(beneath_same_level_m) X(edge_jump_min_m) X(edge_jump_ratio) X(edge_gap_cells) X(edge_height_gap_m) X(edge_ransac_threshold_m) X(edge_ransac_iterations) X(edge_min_points) X(edge_max_lines_per_group) X(edge_max_tilt_deg) X(edge_max_axis_deg) \
  X(normal_edge_blur_cells) X(normal_edge_canny_low) X(normal_edge_canny_high) X(normal_edge_min_contour_px) X(normal_edge_hough_theta_deg) X(normal_edge_hough_votes_px) \
  X(normal_edge_hough_min_length_px) X(normal_edge_hough_max_gap_px) X(normal_edge_side_cells) X(normal_edge_min_bend_deg) X(normal_edge_max_tilt_deg) \
  X(normal_edge_max_axis_deg) X(normal_edge_max_range_m) X(normal_edge_merge_bin_m) X(normal_edge_merge_bin_deg) \
  X(horizontal_tol_deg) X(vertical_tol_deg) X(merge_bin_m) X(merge_gap_m)      \
  X(extent_percentile) X(riser_min_m) X(riser_max_m) X(tread_min_m) X(tread_max_m) X(step_rule_min_m)    \
  X(step_rule_max_m) X(din_tolerance) X(level_max_spread_of_rise) X(landing_min_depth_m) X(min_step_width_m) X(max_lateral_gap_m) X(min_riser_seen_fraction) X(min_steps)           \
  X(max_sample_points) X(max_other_points) X(max_planes) X(max_edges)
#define STAIRS_VERIFICATION_FIELDS(X)                                                                         \
  X(riser_support) X(foot_support) X(widths) X(alignment) X(regularity) X(lateral_samples) X(vertical_samples)  \
  X(lateral_margin) X(vertical_margin) X(max_nosing_overhang_m) X(min_probe_elevation_deg) X(probe_offset_m) X(probe_depth_m) X(solid_tolerance_m) X(solid_tolerance_per_m2)          \
  X(max_see_through) X(min_decided_probes) X(border_margin_px) X(end_offset_m) X(min_width_ratio) X(min_lateral_overlap)        \
  X(max_riser_yaw_spread_deg) X(rise_tolerance_m) X(run_tolerance_m) X(min_run_m) \
  X(rise_outlier_m) X(run_outlier_m) X(regular_steps_for_an_outlier)
#define STAIRS_IMU_FIELDS(X)                                                                              \
  X(to_camera_roll_deg) X(to_camera_pitch_deg) X(to_camera_yaw_deg) X(time_constant_s) X(max_force_deviation) \
  X(max_age_s) X(warmup_s) X(plane_agreement_deg) X(max_disagreement_deg)
  for (const auto& [key, value] : j.items()) {
#define STAIRS_READ(name)                     \
  if (key == #name) {                         \
    read_field(value, json_path, key, c.name); \
    continue;                                 \
  }
    STAIRS_PERCEPTION_FIELDS(STAIRS_READ)
#undef STAIRS_READ
    if (key == "verification") {
      read_section(value, json_path, key, [&](const std::string& k, const nlohmann::json& v, const std::string& name) {
#define STAIRS_READ(field)                                  \
  if (k == #field) {                                        \
    read_field(v, json_path, name, c.verification.field);   \
    return true;                                            \
  }
        STAIRS_VERIFICATION_FIELDS(STAIRS_READ)
#undef STAIRS_READ
        return false;
      });
      continue;
    }
    if (key == "imu") {
      read_section(value, json_path, key, [&](const std::string& k, const nlohmann::json& v, const std::string& name) {
#define STAIRS_READ(field)                         \
  if (k == #field) {                               \
    read_field(v, json_path, name, c.imu.field);   \
    return true;                                   \
  }
        STAIRS_IMU_FIELDS(STAIRS_READ)
#undef STAIRS_READ
        return false;
      });
      continue;
    }
    throw std::runtime_error(json_path + ": unknown perception config key '" + key + "'");
  }
#undef STAIRS_PERCEPTION_FIELDS
#undef STAIRS_VERIFICATION_FIELDS
#undef STAIRS_IMU_FIELDS
  const VerificationConfig& v = c.verification;
  const auto require = [&](bool ok, const char* key, const char* range) {
    if (!ok) throw std::runtime_error(json_path + ": perception config key 'verification." + key + "' must be " + range);
  };
  require(v.lateral_samples >= 1 && v.lateral_samples <= 64, "lateral_samples", "within 1..64");
  require(v.vertical_samples >= 1 && v.vertical_samples <= 64, "vertical_samples", "within 1..64");
  require(v.lateral_margin >= 0 && v.lateral_margin < 0.5f, "lateral_margin", "within [0, 0.5)");
  require(v.vertical_margin >= 0 && v.vertical_margin < 0.5f, "vertical_margin", "within [0, 0.5)");
  require(v.solid_tolerance_m > 0 && v.solid_tolerance_per_m2 >= 0, "solid_tolerance_m", "> 0 (per_m2 >= 0)");
  require(v.max_see_through >= 0 && v.max_see_through <= 1, "max_see_through", "within 0..1");
  require(v.min_decided_probes >= 1, "min_decided_probes", ">= 1");
  require(v.probe_offset_m > 0 && v.probe_depth_m > 0, "probe_offset_m", "> 0 (probe_depth_m too)");
  require(v.min_width_ratio >= 0 && v.min_width_ratio <= 1, "min_width_ratio", "within 0..1");
  require(v.min_lateral_overlap >= 0 && v.min_lateral_overlap <= 1, "min_lateral_overlap", "within 0..1");
  require(v.max_riser_yaw_spread_deg > 0, "max_riser_yaw_spread_deg", "> 0");
  require(v.rise_tolerance_m > 0 && v.run_tolerance_m > 0, "rise_tolerance_m", "> 0 (run_tolerance_m too)");
  require(v.rise_outlier_m >= v.rise_tolerance_m && v.run_outlier_m >= v.run_tolerance_m, "rise_outlier_m",
          ">= rise_tolerance_m (run_outlier_m >= run_tolerance_m)");
  require(v.regular_steps_for_an_outlier >= 2, "regular_steps_for_an_outlier", ">= 2");
  const ImuConfig& imu = c.imu;
  const auto require_imu = [&](bool ok, const char* key, const char* range) {
    if (!ok) throw std::runtime_error(json_path + ": perception config key 'imu." + key + "' must be " + range);
  };
  require_imu(imu.time_constant_s > 0, "time_constant_s", "> 0");
  require_imu(imu.max_force_deviation > 0 && imu.max_force_deviation < 1, "max_force_deviation", "within (0, 1)");
  require_imu(imu.max_age_s > 0, "max_age_s", "> 0");
  require_imu(imu.warmup_s >= 0, "warmup_s", ">= 0");
  require_imu(imu.plane_agreement_deg >= 0 && imu.plane_agreement_deg <= imu.max_disagreement_deg,
              "plane_agreement_deg", "within 0..max_disagreement_deg");
  require_imu(imu.max_disagreement_deg > 0 && imu.max_disagreement_deg <= 90, "max_disagreement_deg", "within (0, 90]");
  if (c.grid_cell_px < 1 || c.normal_radius_cells < 1 || c.max_sample_points < 1 ||
      c.max_sample_points > 1024 || c.max_planes < 1 || c.max_planes > 192 || c.min_steps < 1 ||
      c.normal_edge_blur_cells < 0 || c.normal_edge_canny_low < 0 || c.normal_edge_canny_high < c.normal_edge_canny_low ||
      !(c.normal_edge_hough_theta_deg > 0) || c.normal_edge_side_cells < 1 || !(c.normal_edge_merge_bin_m > 0) ||
      !(c.normal_edge_merge_bin_deg > 0) || c.max_edges < 0 || c.max_edges > 256 ||
      !(c.cell_min_valid_fraction > 0) || c.cell_min_valid_fraction > 1 || !(c.cell_valid_fraction_range_m > 0) ||
      !(c.level_max_spread_of_rise > 0) || c.level_max_spread_of_rise > 1)
    throw std::runtime_error(json_path + ": perception config value out of range");
  return c;
}

}  // namespace stairs
