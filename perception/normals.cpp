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
  const uint16_t span = static_cast<uint16_t>(hi - lo);
  const float cell_area = static_cast<float>(g.cell_px * g.cell_px);
  const float range_units = static_cast<float>(cfg.cell_valid_fraction_range_m / frame.depth_scale);
  const int cp = g.cell_px, cols = g.width * cp;
  const float scale = static_cast<float>(frame.depth_scale), cx = static_cast<float>(K.cx),
              cy = static_cast<float>(K.cy), inv_fx = static_cast<float>(1.0 / K.fx),
              inv_fy = static_cast<float>(1.0 / K.fy);
  NormalGrid::Scratch& s = g.scratch;
  s.column_min.resize(cols);
  s.column_limit.resize(cols);
  s.column_sum.resize(cols);
  s.column_count.resize(cols);
  s.column_row_sum.resize(cols);
  s.cell_min.resize(g.width);
  uint16_t* cmin = s.column_min.data();
  uint16_t* climit = s.column_limit.data();
  uint32_t* csum = s.column_sum.data();
  uint32_t* ccount = s.column_count.data();
  uint32_t* crows = s.column_row_sum.data();
  // One band of cells at a time, in two contiguous sweeps over its pixel rows
  // (column-wise, so the compiler vectorises them): the nearest valid depth of
  // each cell, then the sums of its pixels on that nearest surface.
  for (int gy = 0; gy < g.height; ++gy) {
    const int v0 = gy * cp;
    std::fill(cmin, cmin + cols, uint16_t{65535});
    for (int v = v0; v < v0 + cp; ++v) {
      const uint16_t* row = frame.depth.data() + static_cast<size_t>(v) * K.width;
      for (int u = 0; u < cols; ++u) {
        const uint16_t d = row[u];
        const uint16_t x = static_cast<uint16_t>(d - lo) <= span ? d : uint16_t{65535};
        cmin[u] = std::min(cmin[u], x);
      }
    }
    for (int gx = 0; gx < g.width; ++gx) {
      const uint16_t m = *std::min_element(cmin + gx * cp, cmin + (gx + 1) * cp);
      s.cell_min[gx] = m;
      // No valid pixel: a limit below every valid depth (lo >= 1).
      const uint32_t limit = m == 65535 ? 0u : m + static_cast<uint32_t>(cfg.jump_ratio * m);
      std::fill(climit + gx * cp, climit + (gx + 1) * cp, static_cast<uint16_t>(std::min<uint32_t>(limit, 65535)));
    }
    std::fill(csum, csum + cols, 0u);
    std::fill(ccount, ccount + cols, 0u);
    std::fill(crows, crows + cols, 0u);
    for (int v = v0; v < v0 + cp; ++v) {
      const uint16_t* row = frame.depth.data() + static_cast<size_t>(v) * K.width;
      for (int u = 0; u < cols; ++u) {
        const uint16_t d = row[u];
        const uint32_t on = static_cast<uint32_t>(d >= lo) & static_cast<uint32_t>(d <= climit[u]);
        csum[u] += on * d;
        ccount[u] += on;
        crows[u] += on * static_cast<uint32_t>(v);
      }
    }
    for (int gx = 0; gx < g.width; ++gx) {
      const int i = g.index(gx, gy);
      g.has_point[i] = 0;
      const uint16_t d_min = s.cell_min[gx];
      if (d_min == 65535) continue;
      uint32_t sum = 0, n = 0, su = 0, sv = 0;
      for (int u = gx * cp; u < (gx + 1) * cp; ++u) {
        sum += csum[u];
        n += ccount[u];
        su += ccount[u] * static_cast<uint32_t>(u);
        sv += crows[u];
      }
      const float fraction = d_min <= range_units ? cfg.cell_min_valid_fraction
                                                  : cfg.cell_min_valid_fraction * range_units / d_min;
      if (static_cast<float>(n) < std::max(1.0f, std::ceil(fraction * cell_area))) continue;
      // One division per cell: the mean pixel and depth from 1/n.
      const float inv_n = 1.0f / static_cast<float>(n);
      const float z = static_cast<float>(sum) * scale * inv_n;
      g.points[i] = {(static_cast<float>(su) * inv_n - cx) * inv_fx * z, (static_cast<float>(sv) * inv_n - cy) * inv_fy * z, z};
      g.inverse_depth[i] = 1.0f / z;
      g.has_point[i] = 1;
    }
  }
}

// A row of cells (normal and depth, struct-of-arrays) and its neighbours at one offset.
struct RowView {
  const float *nx, *ny, *nz, *z;
};

// Adds each neighbour's normal to its cell's sum when both lie on one surface.
void smooth_row(RowView c, RowView k, int count, float cos_smooth, float jump, float* __restrict sx,
                float* __restrict sy, float* __restrict sz) {
  for (int i = 0; i < count; ++i) {
    const float dot = k.nx[i] * c.nx[i] + k.ny[i] * c.ny[i] + k.nz[i] * c.nz[i];
    const float near_z = c.z[i] < k.z[i] ? c.z[i] : k.z[i];
    const float dz = c.z[i] - k.z[i], limit = jump * near_z;
    // Selects, not branches, so that it vectorises (-fopt-info-vec).
    float w = dot > cos_smooth ? 1.0f : 0.0f;
    w = dz <= limit ? w : 0.0f;
    w = -dz <= limit ? w : 0.0f;
    sx[i] += w * k.nx[i];
    sy[i] += w * k.ny[i];
    sz[i] += w * k.nz[i];
  }
}

// Normals by cross products of neighbours radius_cells away (thesis 3.2).
void raw_normals(const NormalsConfig& cfg, NormalGrid& g) {
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
    const float ic = g.inverse_depth[c], il = g.inverse_depth[lo], ih = g.inverse_depth[hi];
    if (std::abs(il + ih - 2 * ic) <= cfg.inverse_depth_kink_per_m) return;
    (std::abs(il - ic) > std::abs(ih - ic) ? lo : hi) = c;
  };
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
      g.normals[c] = nrm;
      g.has_normal[c] = 1;
    }
  }
}

// 3x3 mean over neighbours on the same surface: noise down, edges kept. On
// struct-of-arrays copies, one neighbour offset at a time along a row, so the
// compiler runs four cells per instruction. A cell without a normal has a
// zero one (its dot is 0, never above cos_smooth) and adds nothing.
void smooth_normals(const NormalsConfig& cfg, NormalGrid& g) {
  const size_t n = g.normals.size();
  NormalGrid::Scratch& sc = g.scratch;
  for (auto* v : {&sc.nx, &sc.ny, &sc.nz, &sc.z, &sc.sx, &sc.sy, &sc.sz}) v->assign(n, 0.0f);
  for (size_t i = 0; i < n; ++i) {
    sc.nx[i] = g.normals[i].x(), sc.ny[i] = g.normals[i].y(), sc.nz[i] = g.normals[i].z();
    sc.z[i] = g.points[i].z();
  }
  const float cos_smooth = std::cos(cfg.smooth_max_angle_deg * static_cast<float>(M_PI) / 180.0f);
  const float jump = cfg.jump_ratio * 2 * cfg.radius_cells;
  for (int gy = 1; gy < g.height - 1; ++gy) {
    const int c0 = gy * g.width + 1, count = g.width - 2;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int k0 = c0 + dy * g.width + dx;
        smooth_row({sc.nx.data() + c0, sc.ny.data() + c0, sc.nz.data() + c0, sc.z.data() + c0},
                   {sc.nx.data() + k0, sc.ny.data() + k0, sc.nz.data() + k0, sc.z.data() + k0}, count, cos_smooth,
                   jump, sc.sx.data() + c0, sc.sy.data() + c0, sc.sz.data() + c0);
      }
  }
  for (size_t i = 0; i < n; ++i)
    if (g.has_normal[i]) g.normals[i] = Eigen::Vector3f(sc.sx[i], sc.sy[i], sc.sz[i]).normalized();
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
  g.inverse_depth.assign(n, 0.0f);
  g.has_point.assign(n, 0);
  g.has_normal.assign(n, 0);
  if (n == 0) return;
  cell_means(frame, cfg, g);
  raw_normals(cfg, g);
  if (cfg.smooth) smooth_normals(cfg, g);
}

}  // namespace stairs
