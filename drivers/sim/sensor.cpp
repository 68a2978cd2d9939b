#include "drivers/sim/sensor.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace stairs::sim {
namespace {
constexpr double kRad = M_PI / 180.0;

// Pixels with a neighbour whose depth differs by more than edge_jump_ratio.
std::vector<uint8_t> edge_pixels(const SensorModel& m, int W, int H, const std::vector<float>& depth_m) {
  const float ratio = static_cast<float>(m.edge_jump_ratio);
  auto jump = [ratio](float a, float b) { return std::abs(a - b) > ratio * std::max(std::max(a, b), 0.5f); };
  std::vector<uint8_t> edge(depth_m.size(), 0);
  for (int v = 0; v < H; ++v)
    for (int u = 0; u < W; ++u) {
      const size_t i = static_cast<size_t>(v) * W + u;
      if (u + 1 < W && jump(depth_m[i], depth_m[i + 1])) edge[i] = edge[i + 1] = 1;
      if (v + 1 < H && jump(depth_m[i], depth_m[i + W])) edge[i] = edge[i + W] = 1;
    }
  return edge;
}
}  // namespace

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
  const std::vector<uint8_t> edge = edge_pixels(m, W, H, scratch_m);
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

void apply_depth_warp(const SensorModel& m, const Intrinsics& K, std::vector<float>& depth_m) {
  const double half_diagonal2 = 0.25 * (static_cast<double>(K.width) * K.width + static_cast<double>(K.height) * K.height);
  for (int v = 0; v < K.height; ++v)
    for (int u = 0; u < K.width; ++u) {
      float& d = depth_m[static_cast<size_t>(v) * K.width + u];
      const double rho2 = ((u - K.cx) * (u - K.cx) + (v - K.cy) * (v - K.cy)) / half_diagonal2;
      d = static_cast<float>(d * (1.0 + m.depth_warp * (rho2 - 0.5)));
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


SensorModel sensor_preset(const std::string& name) {
  SensorModel m;
  if (name == "kinect1") return m;
  if (name == "kinect2") {
    m.kind = SensorKind::KinectV2;
    m.shadow = false;        // the illuminator sits beside the lens
    m.quantisation = false;  // metric depth, 1 mm in the PNG
    m.holes_per_megapixel = 100.0;
    return m;
  }
  if (name == "d435") {
    m.kind = SensorKind::StereoD4xx;
    m.min_range_m = 0.3;
    m.max_range_m = 5.0;
    m.projector_offset_m = m.stereo_baseline_m;  // the right imager's shadow
    m.quantisation = false;
    return m;
  }
  throw std::invalid_argument("unknown sensor '" + name + "' (kinect1, kinect2, d435)");
}

std::string sensor_name(SensorKind kind) {
  switch (kind) {
    case SensorKind::KinectV2: return "kinect2";
    case SensorKind::StereoD4xx: return "d435";
    default: return "kinect1";
  }
}

Intrinsics sensor_intrinsics(SensorKind kind, int width, int height) {
  // Native depth modes: Kinect v1 640x480 f 525; Kinect v2 512x424 f 365; D435 640x480 f 383.
  Intrinsics n{640, 480, 525.0, 525.0, 319.5, 239.5};
  if (kind == SensorKind::KinectV2) n = {512, 424, 365.0, 365.0, 255.5, 211.5};
  if (kind == SensorKind::StereoD4xx) n = {640, 480, 383.0, 383.0, 319.5, 239.5};
  if (width <= 0 || height <= 0) return n;
  const double sx = static_cast<double>(width) / n.width, sy = static_cast<double>(height) / n.height;
  return {width, height, n.fx * sx, n.fy * sy, (n.cx + 0.5) * sx - 0.5, (n.cy + 0.5) * sy - 0.5};
}


void apply_flying_pixels(const SensorModel& m, Rng& rng, int W, int H, std::vector<float>& depth_m,
                         std::vector<float>& scratch_m) {
  scratch_m = depth_m;
  const std::vector<uint8_t> edge = edge_pixels(m, W, H, scratch_m);
  for (int v = 1; v + 1 < H; ++v)
    for (int u = 1; u + 1 < W; ++u) {
      const size_t i = static_cast<size_t>(v) * W + u;
      if (!edge[i] || scratch_m[i] <= 0.0f || rng.uniform() >= m.flying_fraction) continue;
      float lo = scratch_m[i], hi = scratch_m[i];
      for (int dv = -1; dv <= 1; ++dv)
        for (int du = -1; du <= 1; ++du) {
          const float z = scratch_m[i + static_cast<long>(dv) * W + du];
          if (z > 0.0f) lo = std::min(lo, z), hi = std::max(hi, z);
        }
      depth_m[i] = lo + static_cast<float>(rng.uniform()) * (hi - lo);
    }
}

void apply_multipath(const SensorModel& m, const Intrinsics& K, const Geometry& g, const Eigen::Isometry3d& T,
                     const ZBuffer& zb, std::vector<float>& depth_m) {
  const Eigen::Matrix3d to_cam = T.linear().transpose();
  std::vector<Eigen::Vector3f> normals;  // camera frame, per planar face
  for (const Face& f : g.faces) normals.push_back((to_cam * f.normal).cast<float>());
  const int W = K.width, H = K.height;
  const int32_t faces = static_cast<int32_t>(normals.size());
  const std::vector<float> z0 = depth_m;
  auto point = [&](int u, int v, float z) {
    return Eigen::Vector3f(static_cast<float>((u - K.cx) / K.fx) * z, static_cast<float>((v - K.cy) / K.fy) * z, z);
  };
  const float range = static_cast<float>(m.multipath_range_m), bias = static_cast<float>(m.multipath_bias_m);
  const int dirs[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
  for (int v = 0; v < H; ++v)
    for (int u = 0; u < W; ++u) {
      const size_t i = static_cast<size_t>(v) * W + u;
      const int32_t id = zb.id[i];
      if (z0[i] <= 0.0f || id < 0 || id >= faces) continue;
      const Eigen::Vector3f p = point(u, v, z0[i]), n = normals[static_cast<size_t>(id)];
      const int reach = std::min(64, static_cast<int>(std::ceil(K.fx * range / z0[i])));
      float nearest = range;
      for (const auto& d : dirs)
        for (int s = 1; s <= reach; ++s) {
          const int uu = u + d[0] * s, vv = v + d[1] * s;
          if (uu < 0 || vv < 0 || uu >= W || vv >= H) break;
          const size_t j = static_cast<size_t>(vv) * W + uu;
          const int32_t other = zb.id[j];
          if (other == id) continue;
          if (other < 0 || other >= faces || z0[j] <= 0.0f) break;
          const Eigen::Vector3f q = point(uu, vv, z0[j]);
          // A face standing in front of this one and turned towards it: a concave corner.
          if ((q - p).dot(n) > 0.0f && normals[static_cast<size_t>(other)].dot(n) < 0.7f)
            nearest = std::min(nearest, (q - p).norm());
          break;
        }
      if (nearest < range) depth_m[i] += bias * (1.0f - nearest / range);
    }
}

void apply_tof_noise(const SensorModel& m, Rng& rng, std::vector<float>& depth_m) {
  FastNormal normal(rng);
  const float a = static_cast<float>(m.tof_sigma_a_m), b = static_cast<float>(m.tof_sigma_b);
  for (float& z : depth_m)
    if (z > 0.0f) z += normal() * (a + b * z);
}

void apply_stereo_noise(const SensorModel& m, double focal_px, Rng& rng, std::vector<float>& depth_m) {
  FastNormal normal(rng);
  const float fb = static_cast<float>(focal_px * m.stereo_baseline_m), sigma = static_cast<float>(m.stereo_sigma_px);
  for (float& z : depth_m) {
    if (z <= 0.0f) continue;
    const float d = fb / z + normal() * sigma;
    z = d > 0.0f ? fb / d : 0.0f;
  }
}

void apply_edge_holes(const SensorModel& m, Rng& rng, int W, int H, std::vector<float>& depth_m) {
  const std::vector<uint8_t> edge = edge_pixels(m, W, H, depth_m);
  for (size_t i = 0; i < depth_m.size(); ++i)
    if (edge[i] && rng.uniform() < m.edge_hole_fraction) depth_m[i] = 0.0f;
}

void apply_dark_dropout(const SensorModel& m, const std::vector<uint8_t>& dark, const ZBuffer& zb, Rng& rng,
                        std::vector<float>& depth_m) {
  for (size_t i = 0; i < depth_m.size(); ++i) {
    const int32_t id = zb.id[i];
    if (id >= 0 && id < static_cast<int32_t>(dark.size()) && dark[static_cast<size_t>(id)] &&
        rng.uniform() < m.dark_dropout)
      depth_m[i] = 0.0f;
  }
}

}  // namespace stairs::sim
