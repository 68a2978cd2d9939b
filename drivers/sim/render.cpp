#include "drivers/sim/render.hpp"

#include "drivers/sim/pose_truth.hpp"
#include "drivers/sim/rng.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace stairs::sim {
Renderer::Renderer(const Scene& scene, const Intrinsics& K, const SensorModel& sensor, uint64_t seed)
    : scene_(scene), geometry_(build_geometry(scene)), K_(K), projector_K_(K), sensor_(sensor), seed_(seed) {
  if (K.width <= 0 || K.height <= 0 || K.fx <= 0 || K.fy <= 0)
    throw std::invalid_argument("stairs-sim: invalid intrinsics");
  // The projector sits to the camera's right, so it sees a point further left
  // in its image by fx * offset / z: widen its image to the left to cover the
  // camera's whole view down to the minimum range.
  const int margin = static_cast<int>(std::ceil(K.fx * sensor.projector_offset_m / sensor.min_range_m)) + 2;
  projector_K_.width = K.width + margin;
  projector_K_.cx = K.cx + margin;
  for (const Face& f : geometry_.faces) dark_.push_back(scene.dark_treads && f.part == FacePart::Tread);
}

int Renderer::visible_min_pixels() const {
  return std::max(1, static_cast<int>(std::lround(500.0 * K_.width * K_.height / (640.0 * 480.0))));
}

DepthImage Renderer::render(const Eigen::Isometry3d& T, int64_t utime, int32_t seq) {
  const SensorModel& m = sensor_;
  auto on = [&](bool effect) { return !m.perfect && effect; };
  const int W = K_.width, H = K_.height;
  const size_t N = static_cast<size_t>(W) * H;
  const double res_scale = W / 640.0;
  Rng rng(frame_seed(seed_, seq));

  rasterise(geometry_, T, K_, camera_zb_);
  last_pose_ = T;
  have_last_pose_ = true;
  depth_m_.assign(N, 0.0f);
  for (size_t i = 0; i < N; ++i)
    if (camera_zb_.inv_z[i] > 0.0f) depth_m_[i] = 1.0f / camera_zb_.inv_z[i];

  // Order: surfaces the projector or the camera cannot see, then the edges
  // wander, then the noise of what remains, then pixels without a return.
  if (on(m.shadow)) {
    Eigen::Isometry3d projector = T;
    projector.translate(Eigen::Vector3d(m.projector_offset_m, 0.0, 0.0));
    rasterise(geometry_, projector, projector_K_, projector_zb_);
    apply_projector_shadow(m, K_, projector_K_, camera_zb_, projector_zb_, depth_m_);
  }
  if (on(m.grazing_dropout)) apply_grazing_dropout(m, K_, geometry_, T, camera_zb_, rng, depth_m_);
  switch (m.perfect ? SensorKind::KinectV1 : m.kind) {
    case SensorKind::KinectV1:
      if (on(m.lateral_noise)) apply_lateral_noise(m, m.lateral_sigma_px * res_scale, rng, W, H, depth_m_, scratch_m_);
      if (on(m.axial_noise) || on(m.quantisation))
        apply_axial_noise(m, on(m.axial_noise), on(m.quantisation), rng, depth_m_);
      break;
    case SensorKind::KinectV2:
      if (m.multipath) apply_multipath(m, K_, geometry_, T, camera_zb_, depth_m_);
      if (m.lateral_noise) apply_flying_pixels(m, rng, W, H, depth_m_, scratch_m_);
      if (m.axial_noise) apply_tof_noise(m, rng, depth_m_);
      break;
    case SensorKind::StereoD4xx:
      if (m.lateral_noise) apply_edge_holes(m, rng, W, H, depth_m_);
      if (m.axial_noise) apply_stereo_noise(m, K_.fx, rng, depth_m_);
      break;
  }
  // A dark surface returns nothing on dark_dropout of its pixels, after the edge effects: a pixel
  // without a return is no depth edge (before them, a D435's edge holes spread the dropout to the
  // neighbours: 74 % of a dark tread's pixels read nothing for 50 %).
  if (!m.perfect && scene_.dark_treads) apply_dark_dropout(m, dark_, camera_zb_, rng, depth_m_);
  if (on(m.depth_warp != 0.0)) apply_depth_warp(m, K_, depth_m_);
  if (on(m.holes)) apply_holes(m, res_scale, rng, W, H, depth_m_);

  DepthImage img;
  img.K = K_;
  img.depth_scale = 0.001;
  img.utime = utime;
  img.seq = seq;
  img.depth.assign(N, 0);
  for (size_t i = 0; i < N; ++i) {
    const float z = depth_m_[i];
    if (z >= m.min_range_m && z <= m.max_range_m) img.depth[i] = static_cast<uint16_t>(z * 1000.0f + 0.5f);
  }
  return img;
}

GroundTruthFrame Renderer::truth(const Eigen::Isometry3d& T, double timestamp_s, const DepthImage& rendered) const {
  if (rendered.K.width != K_.width || rendered.K.height != K_.height ||
      rendered.depth.size() != static_cast<size_t>(K_.width) * K_.height)
    throw std::invalid_argument("Renderer::truth: image size differs from the renderer's intrinsics");
  GroundTruthFrame fr;
  fr.timestamp = timestamp_s;
  fr.pitch_deg = pitch_deg(T);
  fr.roll_deg = roll_deg(T);
  fr.height_m = height_m(scene_, T);
  fr.distance_m = distance_m(scene_, T);
  fr.position_m = T.translation();
  fr.orientation = Eigen::Quaterniond(T.linear()).normalized();

  // The ids of the last render when it had this pose (the usual case), else a
  // fresh rasterisation.
  ZBuffer fresh;
  const bool same = have_last_pose_ && (T.matrix().array() == last_pose_.matrix().array()).all();
  if (!same) rasterise(geometry_, T, K_, fresh);
  const ZBuffer& zb = same ? camera_zb_ : fresh;
  int steps = 0;
  for (const Face& f : geometry_.faces) steps = std::max(steps, f.step + 1);
  std::vector<int> riser(static_cast<size_t>(steps), 0), tread(static_cast<size_t>(steps), 0);
  for (size_t i = 0; i < rendered.depth.size(); ++i) {
    const int32_t id = zb.id[i];
    if (rendered.depth[i] == 0 || id < 0 || id >= static_cast<int32_t>(geometry_.faces.size())) continue;
    const Face& f = geometry_.faces[static_cast<size_t>(id)];
    if (f.part == FacePart::Riser) ++riser[static_cast<size_t>(f.step)];
    if (f.part == FacePart::Tread) ++tread[static_cast<size_t>(f.step)];
  }
  const int min_px = visible_min_pixels();
  for (int k = 0; k < steps; ++k)
    if (riser[static_cast<size_t>(k)] >= min_px || tread[static_cast<size_t>(k)] >= min_px) fr.visible_steps.push_back(k);
  return fr;
}

GroundTruth Renderer::stair_truth() const { return scene_truth(scene_); }

}  // namespace stairs::sim
