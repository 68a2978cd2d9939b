#include "drivers/sim/sensor.hpp"

#include <algorithm>
#include <cmath>

namespace stairs::sim {
namespace {
constexpr double kRad = M_PI / 180.0;
}

SensorModel perfect_sensor() {
  SensorModel m;
  m.perfect = true;
  return m;
}

void apply_projector_shadow(const SensorModel& m, const Intrinsics& K, const Intrinsics& P, const ZBuffer& camera_zb,
                            const ZBuffer& projector_zb, std::vector<float>& depth_m) {
  const int W = K.width, H = K.height;
  for (int v = 0; v < H; ++v) {
    const double y = (v - K.cy) / K.fy;
    const double vp = P.fy * y + P.cy + 0.5;  // same rows: the offset is along x
    if (vp < 0.0 || vp >= P.height) continue;
    const float* zrow = projector_zb.inv_z.data() + static_cast<size_t>(vp) * P.width;
    float* row = depth_m.data() + static_cast<size_t>(v) * W;
    const float* inv_z = camera_zb.inv_z.data() + static_cast<size_t>(v) * W;
    for (int u = 0; u < W; ++u) {
      const double z = row[u];
      if (z <= 0.0) continue;
      const double up = P.fx * ((u - K.cx) / K.fx - m.projector_offset_m * inv_z[u]) + P.cx + 0.5;
      if (up < 0.0 || up >= P.width) continue;
      const float iz = zrow[static_cast<int>(up)];
      if (iz > 0.0f && 1.0 / iz < z - (m.shadow_tolerance_m + 0.01 * z)) row[u] = 0.0f;
    }
  }
}

void apply_grazing_dropout(const SensorModel& m, const Intrinsics& K, const Geometry& g, const Eigen::Isometry3d& T,
                           const ZBuffer& zb, Rng& rng, std::vector<float>& depth_m) {
  const Eigen::Matrix3d to_cam = T.linear().transpose();
  std::vector<Eigen::Vector3d> normals;  // camera frame, per face
  for (const Face& f : g.faces) normals.push_back(to_cam * f.normal);
  const double cos_start = std::cos(m.grazing_start_deg * kRad);
  const double cos2_start = cos_start * cos_start;
  const int W = K.width, H = K.height;
  for (int v = 0; v < H; ++v)
    for (int u = 0; u < W; ++u) {
      const size_t i = static_cast<size_t>(v) * W + u;
      if (depth_m[i] <= 0.0f) continue;
      const Eigen::Vector3d ray((u - K.cx) / K.fx, (v - K.cy) / K.fy, 1.0);
      const int32_t id = zb.id[i];
      const Eigen::Vector3d n = id < static_cast<int32_t>(normals.size())
                                    ? normals[static_cast<size_t>(id)]
                                    : Eigen::Vector3d(to_cam * primitive_normal(g, id, T * (ray * depth_m[i])));
      const double c = n.dot(ray);
      const double r2 = ray.squaredNorm();
      if (c * c >= cos2_start * r2) continue;  // steeper than grazing_start_deg
      const double incidence_deg = std::acos(std::abs(c) / std::sqrt(r2)) / kRad;
      const double p = (incidence_deg - m.grazing_start_deg) / (m.grazing_full_deg - m.grazing_start_deg);
      if (rng.uniform() < p) depth_m[i] = 0.0f;
    }
}

void apply_lateral_noise(const SensorModel& m, double sigma_px, Rng& rng, int W, int H, std::vector<float>& depth_m,
                         std::vector<float>& scratch_m) {
  scratch_m = depth_m;
  const float ratio = static_cast<float>(m.edge_jump_ratio);
  auto jump = [ratio](float a, float b) { return std::abs(a - b) > ratio * std::max(std::max(a, b), 0.5f); };
  std::vector<uint8_t> edge(depth_m.size(), 0);
  for (int v = 0; v < H; ++v)
    for (int u = 0; u < W; ++u) {
      const size_t i = static_cast<size_t>(v) * W + u;
      if (u + 1 < W && jump(scratch_m[i], scratch_m[i + 1])) edge[i] = edge[i + 1] = 1;
      if (v + 1 < H && jump(scratch_m[i], scratch_m[i + W])) edge[i] = edge[i + W] = 1;
    }
  FastNormal normal(rng);
  for (int v = 0; v < H; ++v)
    for (int u = 0; u < W; ++u) {
      const size_t i = static_cast<size_t>(v) * W + u;
      if (!edge[i]) continue;
      const int us = std::clamp(u + static_cast<int>(std::lround(normal() * sigma_px)), 0, W - 1);
      const int vs = std::clamp(v + static_cast<int>(std::lround(normal() * sigma_px)), 0, H - 1);
      depth_m[i] = scratch_m[static_cast<size_t>(vs) * W + us];
    }
}

void apply_axial_noise(const SensorModel& m, bool noise, bool quantise, Rng& rng, std::vector<float>& depth_m) {
  // The noise added before the quantisation is reduced by the quantisation's
  // own variance (step^2 / 12), so that the total matches sigma(z), which was
  // measured on quantised depth. Float and two divisions per pixel: this loop
  // is the largest cost of a frame.
  const float fb = static_cast<float>(m.focal_px * m.baseline_m);
  const float a = static_cast<float>(m.sigma_a_m), b = static_cast<float>(m.sigma_b_per_m);
  const float c = static_cast<float>(m.sigma_c_m);
  const float sub = static_cast<float>(m.subpixel), inv_sub = 1.0f / sub;
  const float q = quantise ? 1.0f / (12.0f * fb * fb * sub * sub) : 0.0f;  // var_q = q z^4
  FastNormal normal(rng);
  for (float& z : depth_m) {
    if (z <= 0.0f) continue;
    const float inv_z = 1.0f / z;
    float d = fb * inv_z;
    if (noise) {
      const float sigma_z = a + b * (z - c) * (z - c);
      const float z2 = z * z;
      const float var = sigma_z * sigma_z - q * z2 * z2;
      if (var > 0.0f) d += normal() * std::sqrt(var) * d * inv_z;  // dd = dz * fb / z^2
    }
    if (quantise) d = std::floor(d * sub + 0.5f) * inv_sub;
    z = d > 0.0f ? fb / d : 0.0f;
  }
}

void apply_holes(const SensorModel& m, double radius_scale, Rng& rng, int W, int H, std::vector<float>& depth_m) {
  const int count = static_cast<int>(std::lround(m.holes_per_megapixel * W * H / 1e6));
  for (int h = 0; h < count; ++h) {
    const int cu = static_cast<int>(rng.uniform() * W), cv = static_cast<int>(rng.uniform() * H);
    const double r = m.hole_radius_px * radius_scale * (0.5 + rng.uniform());
    const int ri = static_cast<int>(std::ceil(r));
    for (int v = std::max(0, cv - ri); v <= std::min(H - 1, cv + ri); ++v)
      for (int u = std::max(0, cu - ri); u <= std::min(W - 1, cu + ri); ++u)
        if ((u - cu) * (u - cu) + (v - cv) * (v - cv) <= r * r) depth_m[static_cast<size_t>(v) * W + u] = 0.0f;
  }
}

}  // namespace stairs::sim
