#include "tracker/config.hpp"

#include <nlohmann/json.hpp>

#include <fstream>
#include <stdexcept>

namespace stairs {

namespace {

template <class T>
void read_field(const nlohmann::json& value, const std::string& path, const std::string& key, T& field) {
  const bool ok = std::is_integral<T>::value ? value.is_number_integer() : value.is_number();
  if (!ok) throw std::runtime_error(path + ": key '" + key + "' has the wrong type");
  field = value.get<T>();
}

void require(bool ok, const char* what) {
  if (!ok) throw std::runtime_error(std::string("tracker config: ") + what + " out of range");
}

}  // namespace

void validate(const TrackerConfig& c) {
  require(c.min_seed_steps >= 1, "min_seed_steps");
  require(c.icp_max_distance_m >= c.icp_min_distance_m && c.icp_min_distance_m > 0, "icp_min/max_distance_m");
  require(c.icp_distance_factor > 0 && c.icp_distance_factor < 1, "icp_distance_factor");
  require(c.icp_max_tread_fraction > 0, "icp_max_tread_fraction");
  require(c.icp_iterations_per_stage >= 1, "icp_iterations_per_stage");
  require(c.registration_points_per_plane >= 1 && c.registration_points_per_plane <= 1024,
          "registration_points_per_plane");
  require(c.accept_distance_m > 0, "accept_distance_m");
  require(c.min_inlier_ratio >= 0 && c.min_inlier_ratio <= 1, "min_inlier_ratio");
  require(c.velocity_window_s > 0, "velocity_window_s");
  require(c.relocalise_step_range >= 0 && c.relocalise_step_range <= 10, "relocalise_step_range");
  require(c.max_average_weight >= 1, "max_average_weight");
  require(c.max_model_steps >= 1 && c.max_model_steps <= 1024, "max_model_steps");
  require(c.max_plane_points >= 0 && c.max_plane_points <= 1024, "max_plane_points");
  require(c.default_riser_m > 0 && c.default_tread_m > 0, "default_riser_m/default_tread_m");
  require(c.direction_window >= 1 && c.direction_majority >= 1 && c.direction_majority <= c.direction_window,
          "direction_window/direction_majority");
  require(c.max_reconstructed_gap_steps >= 0, "max_reconstructed_gap_steps");
  require(c.lost_after_s > 0 && c.reset_after_s > 0, "lost_after_s/reset_after_s");
  require(c.time_jump_back_s > 0, "time_jump_back_s");
  require(c.predict_camera_s >= 0 && c.predict_camera_s <= c.max_prediction_s, "predict_camera_s");
  require(c.odometry_max_age_s >= 0 && c.odometry_max_age_s <= 10, "odometry_max_age_s");
  require(c.odometry_max_samples >= 2 && c.odometry_max_samples <= 1000000, "odometry_max_samples");
}

TrackerConfig load_tracker_config(const std::string& json_path) {
  std::ifstream in(json_path);
  if (!in) throw std::runtime_error(json_path + ": cannot open tracker config");
  nlohmann::json j;
  try {
    in >> j;
  } catch (const std::exception& e) {
    throw std::runtime_error(json_path + ": invalid JSON: " + e.what());
  }
  if (!j.is_object()) throw std::runtime_error(json_path + ": tracker config must be a JSON object");
  TrackerConfig c;
#define STAIRS_TRACKER_FIELDS(X)                                                                          \
  X(min_seed_steps) X(icp_max_distance_m) X(icp_max_tread_fraction) X(icp_min_distance_m) X(icp_distance_factor)                    \
  X(icp_iterations_per_stage) X(registration_points_per_plane) X(nosing_weight_points) X(accept_distance_m) \
  X(min_inlier_ratio) X(max_yaw_jump_deg) X(max_translation_jump_m) X(velocity_window_s)                 \
  X(max_prediction_s) X(predict_camera_s) X(odometry_max_age_s) X(odometry_max_samples) X(relocalise_after_s) X(relocalise_step_range) X(match_riser_fraction)              \
  X(match_tread_fraction) X(max_average_weight) X(max_plane_points) X(default_riser_m) X(default_tread_m) \
  X(landing_min_depth_m) X(min_confirmations) X(max_model_steps) X(monotonic_tolerance_m) X(direction_window)                \
  X(direction_majority) X(max_reconstructed_gap_steps) X(reconstruct_tolerance) X(lost_after_s)           \
  X(reset_after_s) X(time_jump_back_s)
  for (const auto& [key, value] : j.items()) {
#define STAIRS_READ(name)                      \
  if (key == #name) {                          \
    read_field(value, json_path, key, c.name); \
    continue;                                  \
  }
    STAIRS_TRACKER_FIELDS(STAIRS_READ)
#undef STAIRS_READ
    throw std::runtime_error(json_path + ": unknown tracker config key '" + key + "'");
  }
#undef STAIRS_TRACKER_FIELDS
  try {
    validate(c);
  } catch (const std::exception& e) {
    throw std::runtime_error(json_path + ": " + e.what());
  }
  return c;
}

}  // namespace stairs
