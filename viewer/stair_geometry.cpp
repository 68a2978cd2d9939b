#include "viewer/stair_geometry.hpp"

#include <cmath>

namespace stairs::viewer {

std::vector<StepProfile> step_profiles(const Flight& flight) {
  std::vector<StepProfile> out;
  double below_z = 0.0;  // the floor under the first riser
  for (const Step& s : flight.steps) {
    const Eigen::Vector2d nosing(s.nosing_m.x(), s.nosing_m.z());
    const double bottom_z = s.riser_height_m ? nosing.y() - *s.riser_height_m : below_z;
    out.push_back({{nosing.x(), bottom_z}, nosing, {nosing.x() + s.tread_depth_m.value_or(0.0), nosing.y()}});
    below_z = nosing.y();
  }
  return out;
}

std::optional<CameraView> model_camera(const StairModel* model) {
  if (!model || !model->camera_valid) return std::nullopt;
  return CameraView{model->camera_position_m, model->camera_orientation};
}

std::optional<CameraView> truth_camera(const GroundTruthFrame* frame) {
  if (!frame) return std::nullopt;
  return CameraView{frame->position_m, frame->orientation};
}

double half_fov_rad(const Intrinsics* K, bool horizontal) {
  if (!K || K->fx <= 0 || K->fy <= 0) return (horizontal ? 57.0 : 43.0) / 2.0 * M_PI / 180.0;
  return horizontal ? std::atan2(K->width / 2.0, K->fx) : std::atan2(K->height / 2.0, K->fy);
}

}  // namespace stairs::viewer
