#include "perception/normals.hpp"

#include "common/cloud.hpp"

#include <algorithm>
#include <cmath>

namespace stairs {

int grid_cell_px(const NormalsConfig& cfg, int image_width) {
  return std::max(1, static_cast<int>(std::lround(cfg.grid_cell_px * image_width / 640.0)));
}

namespace {

// Each cell is the mean of its nearest surface (pixels within jump_ratio of its nearest one): a mean
// across a depth edge would float between surfaces. Near, a sparse cell is flying pixels; at range
// the sensor drops many, so the valid fraction needed falls as 1/z beyond cell_valid_fraction_range_m.
void cell_means(const DepthImage& frame, const NormalsConfig& cfg, NormalGrid& g) {
  const Intrinsics& K = frame.K;
  const uint16_t lo = static_cast<uint16_t>(std::clamp(cfg.min_depth_m / frame.depth_scale, 1.0, 65535.0));
  const uint16_t hi = static_cast<uint16_t>(std::clamp(cfg.max_depth_m / frame.depth_scale, 1.0, 65535.0));
  const float cell_area = static_cast<float>(g.cell_px * g.cell_px);
  const float range_units = static_cast<float>(cfg.cell_valid_fraction_range_m / frame.depth_scale);
  for (int gy = 0; gy < g.height; ++gy) {
    for (int gx = 0; gx < g.width; ++gx) {
      const int u0 = gx * g.cell_px, v0 = gy * g.cell_px;
      uint16_t d_min = 65535;
      for (int v = v0; v < v0 + g.cell_px; ++v) {
        const uint16_t* row = frame.depth.data() + static_cast<size_t>(v) * K.width;
        for (int u = u0; u < u0 + g.cell_px; ++u)
          if (row[u] >= lo && row[u] <= hi) d_min = std::min(d_min, row[u]);
      }
      const int i = g.index(gx, gy);
      g.has_point[i] = 0;
      if (d_min == 65535) continue;
      const uint32_t limit = d_min + static_cast<uint32_t>(cfg.jump_ratio * d_min);
      uint32_t sum = 0, n = 0, su = 0, sv = 0;
      for (int v = v0; v < v0 + g.cell_px; ++v) {
        const uint16_t* row = frame.depth.data() + static_cast<size_t>(v) * K.width;
        for (int u = u0; u < u0 + g.cell_px; ++u) {
          const uint16_t d = row[u];
          if (d >= lo && d <= limit) {
            sum += d;
            su += u;
            sv += v;
            ++n;
          }
        }
      }
      const float fraction = cfg.cell_min_valid_fraction * std::min(1.0f, range_units / d_min);
      if (static_cast<float>(n) < std::max(1.0f, std::ceil(fraction * cell_area))) continue;
      const float z = static_cast<float>(sum * frame.depth_scale / n);
      g.points[i] = back_project(K, static_cast<float>(su) / n, static_cast<float>(sv) / n, z);
      g.has_point[i] = 1;
    }
  }
}

}  // namespace

void compute_normals(const DepthImage& frame, const NormalsConfig& cfg, NormalGrid& g) {
  g.cell_px = grid_cell_px(cfg, frame.K.width);
  g.margin_cells = cfg.radius_cells;
  g.width = frame.K.width / g.cell_px;
  g.height = frame.K.height / g.cell_px;
  const size_t n = static_cast<size_t>(g.width) * g.height;
  g.points.assign(n, Eigen::Vector3f::Zero());
  g.normals.assign(n, Eigen::Vector3f::Zero());
  g.has_point.assign(n, 0);
  g.has_normal.assign(n, 0);
  if (n == 0) return;
  cell_means(frame, cfg, g);

  const int r = cfg.radius_cells;
  auto near = [&](int a, int b) {
    if (!g.has_point[a] || !g.has_point[b]) return false;
    const float za = g.points[a].z(), zb = g.points[b].z();
    return std::abs(za - zb) <= cfg.jump_ratio * std::min(za, zb) * 2 * r;
  };
  // On a plane 1/z is affine in the image: a kink in 1/z across the centre
  // means the two sides lie on different surfaces; keep the side closer to c.
  auto one_sided = [&](int c, int& lo, int& hi) {
    if (lo == c || hi == c) return;
    const float ic = 1.0f / g.points[c].z(), il = 1.0f / g.points[lo].z(), ih = 1.0f / g.points[hi].z();
    if (std::abs(il + ih - 2 * ic) <= cfg.inverse_depth_kink_per_m) return;
    (std::abs(il - ic) > std::abs(ih - ic) ? lo : hi) = c;
  };
  std::vector<Eigen::Vector3f>& raw = g.normals;
  for (int gy = r; gy < g.height - r; ++gy) {
    for (int gx = r; gx < g.width - r; ++gx) {
      const int c = g.index(gx, gy);
      if (!g.has_point[c]) continue;
      const int l = g.index(gx - r, gy), rt = g.index(gx + r, gy);
      const int up = g.index(gx, gy - r), dn = g.index(gx, gy + r);
      // One-sided differences where a neighbour lies across a depth jump or a corner.
      int a0 = near(c, l) ? l : c, a1 = near(c, rt) ? rt : c;
      int b0 = near(c, up) ? up : c, b1 = near(c, dn) ? dn : c;
      one_sided(c, a0, a1);
      one_sided(c, b0, b1);
      if (a0 == a1 || b0 == b1) continue;
      Eigen::Vector3f nrm = (g.points[a1] - g.points[a0]).cross(g.points[b1] - g.points[b0]);
      const float len = nrm.norm();
      if (!(len > 0.0f)) continue;
      nrm /= len;
      if (nrm.dot(g.points[c]) > 0) nrm = -nrm;
      raw[c] = nrm;
      g.has_normal[c] = 1;
    }
  }
  if (!cfg.smooth) return;
  // 3x3 mean over neighbours on the same surface: noise down, edges kept.
  std::vector<Eigen::Vector3f> smoothed(raw);
  const float cos_smooth = std::cos(cfg.smooth_max_angle_deg * static_cast<float>(M_PI) / 180.0f);
  for (int gy = 1; gy < g.height - 1; ++gy) {
    for (int gx = 1; gx < g.width - 1; ++gx) {
      const int c = g.index(gx, gy);
      if (!g.has_normal[c]) continue;
      Eigen::Vector3f s = Eigen::Vector3f::Zero();
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int k = g.index(gx + dx, gy + dy);
          if (g.has_normal[k] && raw[k].dot(raw[c]) > cos_smooth && near(c, k)) s += raw[k];
        }
      smoothed[c] = s.normalized();
    }
  }
  g.normals.swap(smoothed);
}

}  // namespace stairs
