#include "perception/normals.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace stairs {

int grid_cell_px(const NormalsConfig& cfg, int image_width) {
  return std::max(1, static_cast<int>(std::lround(cfg.grid_cell_px * image_width / 640.0)));
}

namespace {

// A valid depth: within [lo, lo + span] (one unsigned compare; 0, no return, wraps above span).
inline bool valid_depth(uint16_t d, uint16_t lo, uint16_t span) { return static_cast<uint16_t>(d - lo) <= span; }

// The nearest valid depth (in [lo, lo + span], else 65535) of each column over
// a band of `rows` pixel rows. Contiguous and branch-free: it vectorises.
void column_nearest(const uint16_t* band, int stride, int rows, int cols, uint16_t lo, uint16_t span,
                    uint16_t* __restrict nearest) {
  std::fill(nearest, nearest + cols, uint16_t{65535});
  for (int v = 0; v < rows; ++v) {
    const uint16_t* row = band + static_cast<size_t>(v) * stride;
    for (int u = 0; u < cols; ++u) {
      const uint16_t d = row[u];
      nearest[u] = std::min(nearest[u], valid_depth(d, lo, span) ? d : uint16_t{65535});
    }
  }
}

// The valid depths (in [lo, lo + span]) of a cell of side `cp` at column u0 of the band.
uint32_t measured_pixels(const uint16_t* band, int stride, int cp, int u0, uint16_t lo, uint16_t span) {
  uint32_t n = 0;
  for (int v = 0; v < cp; ++v)
    for (int u = u0; u < u0 + cp; ++u) n += valid_depth(band[static_cast<size_t>(v) * stride + u], lo, span);
  return n;
}

// Per column over the band: the sum, count and sum of row indices (from v0) of
// the pixels in [lo, limit[u]], the depths on each cell's nearest surface.
void column_sums(const uint16_t* band, int stride, int v0, int rows, int cols, uint16_t lo,
                 const uint16_t* __restrict limit, uint32_t* __restrict sum, uint32_t* __restrict count,
                 uint32_t* __restrict row_sum) {
  std::fill(sum, sum + cols, 0u);
  std::fill(count, count + cols, 0u);
  std::fill(row_sum, row_sum + cols, 0u);
  for (int v = 0; v < rows; ++v) {
    const uint16_t* row = band + static_cast<size_t>(v) * stride;
    for (int u = 0; u < cols; ++u) {
      const uint16_t d = row[u];
      const uint32_t on = static_cast<uint32_t>(d >= lo) & static_cast<uint32_t>(d <= limit[u]);
      sum[u] += on * d;
      count[u] += on;
      row_sum[u] += on * static_cast<uint32_t>(v0 + v);
    }
  }
}

// Each cell is the mean of its nearest surface (pixels within jump_ratio of its nearest one): a mean
// across a depth edge would float between surfaces. A nearest surface that holds few of the cell's
// measured pixels is flying pixels between surfaces; at range the sensor drops many and surfaces are
// small, so the fraction needed falls as 1/z beyond cell_valid_fraction_range_m. It is a fraction of
// the pixels measured, not of the cell: a surface that absorbs the IR (dark treads) returns nothing on
// half its pixels at random, and counted against the cell's area half its cells had no point. A cell
// counts as measured on at least cell_min_coverage of its pixels, so that a few returns make no mean.
// kCellPx: the cell side when known at compile time (0: g.cell_px), so that
// the loops over a cell's columns unroll (they were a quarter of the stage).
template <int kCellPx>
void cell_means(const DepthImage& frame, const NormalsConfig& cfg, NormalGrid& g) {
  const Intrinsics& K = frame.K;
  const uint16_t lo = static_cast<uint16_t>(std::clamp(cfg.min_depth_m / frame.depth_scale, 1.0, 65535.0));
  const uint16_t hi = static_cast<uint16_t>(std::clamp(cfg.max_depth_m / frame.depth_scale, 1.0, 65535.0));
  const uint16_t span = static_cast<uint16_t>(hi - lo);
  const float cell_area = static_cast<float>(g.cell_px * g.cell_px);
  const float range_units = static_cast<float>(cfg.cell_valid_fraction_range_m / frame.depth_scale);
  const int cp = kCellPx > 0 ? kCellPx : g.cell_px, cols = g.width * cp;
  const float jump_ratio = cfg.jump_ratio;
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
  s.cell_limit.resize(g.width);
  uint16_t* cmin = s.column_min.data();
  const float min_measured = cfg.cell_min_coverage * cell_area;
  uint16_t* climit = s.column_limit.data();
  uint32_t* csum = s.column_sum.data();
  uint32_t* ccount = s.column_count.data();
  uint32_t* crows = s.column_row_sum.data();
  // One band of cells at a time, in two sweeps over its pixel rows: the nearest
  // valid depth of each cell, then the sums of its pixels on that surface.
  for (int gy = 0; gy < g.height; ++gy) {
    const int v0 = gy * cp;
    const uint16_t* band = frame.depth.data() + static_cast<size_t>(v0) * K.width;
    column_nearest(band, K.width, cp, cols, lo, span, cmin);
    for (int gx = 0; gx < g.width; ++gx) {
      const uint16_t* c = cmin + gx * cp;
      uint16_t m = c[0];
      for (int k = 1; k < cp; ++k) m = std::min(m, c[k]);
      s.cell_min[gx] = m;
    }
    // The depth limit of each cell's nearest surface; no valid pixel: a limit
    // below every valid depth (lo >= 1). Signed 32-bit arithmetic and selects,
    // so that it vectorises (the depths fit, the product truncates alike).
    for (int gx = 0; gx < g.width; ++gx) {
      const int32_t m = s.cell_min[gx];
      int32_t limit = m + static_cast<int32_t>(jump_ratio * static_cast<float>(m));
      limit = limit > 65535 ? 65535 : limit;
      s.cell_limit[gx] = static_cast<uint16_t>(m == 65535 ? 0 : limit);
    }
    for (int gx = 0; gx < g.width; ++gx)
      for (int k = 0; k < cp; ++k) climit[gx * cp + k] = s.cell_limit[gx];
    column_sums(band, K.width, v0, cp, cols, lo, climit, csum, ccount, crows);
    for (int gx = 0; gx < g.width; ++gx) {
      const int i = g.index(gx, gy);
      // Every cell is written, those without a point as zeros: the grid is not cleared per frame.
      g.has_point[i] = 0;
      g.filled[i] = 0;
      g.points[i].setZero();
      s.x[i] = s.y[i] = s.z[i] = s.iz[i] = 0.0f;
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
      // A cell its nearest surface fills passes whatever it measured: its pixels are counted
      // only where it does not (most cells are full; the count is a second pass over them).
      const bool fills = static_cast<float>(n) >= std::ceil(fraction * cell_area);
      if (!fills) {
        const float measured = static_cast<float>(measured_pixels(band, K.width, cp, gx * cp, lo, span));
        if (static_cast<float>(n) < std::max(1.0f, std::ceil(fraction * std::max(measured, min_measured)))) continue;
      }
      // One division per cell: the mean pixel and depth from 1/n.
      const float inv_n = 1.0f / static_cast<float>(n);
      const float z = static_cast<float>(sum) * scale * inv_n;
      g.points[i] = {(static_cast<float>(su) * inv_n - cx) * inv_fx * z,
                     (static_cast<float>(sv) * inv_n - cy) * inv_fy * z, z};
      s.x[i] = g.points[i].x(), s.y[i] = g.points[i].y(), s.z[i] = z, s.iz[i] = 1.0f / z;
      g.has_point[i] = 1;
      g.filled[i] = fills;
    }
  }
}

// Lane masks (0 or all ones) and m ? a : b on the bits: the compiler keeps a
// ternary of floats or a bool as a branch, which stops a loop from vectorising
// (-fopt-info-vec); these do not.
using Mask = uint32_t;
inline Mask mask(bool b) { return 0u - static_cast<Mask>(b); }
inline float select(Mask m, float a, float b) {
  uint32_t ai, bi;
  std::memcpy(&ai, &a, sizeof ai);
  std::memcpy(&bi, &b, sizeof bi);
  const uint32_t r = (ai & m) | (bi & ~m);
  float out;
  std::memcpy(&out, &r, sizeof out);
  return out;
}

// Each cell's normal summed with those of its 3x3 neighbours that lie on its
// surface (close in angle, no depth jump), in one pass over the row: the nine
// offsets in registers, not nine passes that add into the sums in memory. The
// terms are added in the same order (rows above to below, left to right).
[[gnu::noinline]] void smooth_row(const float* __restrict nx, const float* __restrict ny, const float* __restrict nz,
                                  const float* __restrict z, int c0, int stride, int count, float cos_smooth,
                                  float jump, float* __restrict sx, float* __restrict sy, float* __restrict sz) {
  for (int i = c0; i < c0 + count; ++i) {
    const float cx = nx[i], cy = ny[i], cz = nz[i], zc = z[i];
    float ax = 0.0f, ay = 0.0f, az = 0.0f;
    const auto add = [&](int k) {
      const float dot = nx[k] * cx + ny[k] * cy + nz[k] * cz;
      const float near_z = select(mask(zc < z[k]), zc, z[k]);
      const float dz = zc - z[k], limit = jump * near_z;
      // Mask selects, not branches, so that it vectorises (-fopt-info-vec).
      const float w = select(mask(dot > cos_smooth) & mask(dz <= limit) & mask(-dz <= limit), 1.0f, 0.0f);
      ax += w * nx[k];
      ay += w * ny[k];
      az += w * nz[k];
    };
    const int up = i - stride, down = i + stride;
    add(up - 1), add(up), add(up + 1), add(i - 1), add(i), add(i + 1), add(down - 1), add(down), add(down + 1);
    sx[i] = ax, sy[i] = ay, sz[i] = az;
  }
}

// Points of a row of cells, struct-of-arrays, from some first cell on.
struct RowPoints {
  const float *x, *y, *z, *iz;
  RowPoints at(int offset) const { return {x + offset, y + offset, z + offset, iz + offset}; }
};

// One row of cells' normals from their neighbours r cells left, right, up and
// down (`lo_a`/`hi_a`, `lo_b`/`hi_b`: the row shifted to them). Selects
// instead of branches, so that it vectorises; out of line, because inlined
// into raw_normals GCC 12 no longer vectorises it (-fopt-info-vec).
[[gnu::noinline]] void normals_row(RowPoints c, RowPoints lo_a, RowPoints hi_a, RowPoints lo_b, RowPoints hi_b,
                                   int count, float jump, float kink, float* __restrict nx, float* __restrict ny,
                                   float* __restrict nz) {
  for (int i = 0; i < count; ++i) {
    const float xc = c.x[i], yc = c.y[i], zc = c.z[i], ic = c.iz[i];
    // A neighbour on the cell's surface: no depth jump between them (z = 0: no point).
    auto near = [&](float zk) {
      const float d = zc - zk, limit = jump * select(mask(zc < zk), zc, zk);
      return mask(d <= limit) & mask(-d <= limit);
    };
    // One-sided differences where a neighbour lies across a depth jump or a
    // corner: on a plane 1/z is affine in the image, so a kink in 1/z across
    // the centre means the two sides lie on different surfaces; the side
    // farther from the centre's 1/z is dropped.
    auto axis = [&](RowPoints lo, RowPoints hi, float& dx, float& dy, float& dz) {
      const float xl = lo.x[i], xh = hi.x[i], yl = lo.y[i], yh = hi.y[i], zl = lo.z[i], zh = hi.z[i];
      const float il = lo.iz[i], ih = hi.iz[i];
      const Mask near_lo = near(zl), near_hi = near(zh);
      const Mask kinked = near_lo & near_hi & mask(std::abs(il + ih - 2 * ic) > kink);
      const Mask drop_lo = kinked & mask(std::abs(il - ic) > std::abs(ih - ic));
      const Mask use_lo = near_lo & ~drop_lo, use_hi = near_hi & ~(kinked & ~drop_lo);
      dx = select(use_hi, xh, xc) - select(use_lo, xl, xc);
      dy = select(use_hi, yh, yc) - select(use_lo, yl, yc);
      dz = select(use_hi, zh, zc) - select(use_lo, zl, zc);
      return use_lo | use_hi;
    };
    float ax, ay, az, bx, by, bz;
    const Mask ok_a = axis(lo_a, hi_a, ax, ay, az), ok_b = axis(lo_b, hi_b, bx, by, bz);
    float cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
    const float len = std::sqrt(cx * cx + cy * cy + cz * cz);
    const Mask ok = mask(zc > 0) & ok_a & ok_b & mask(len > 0.0f);
    const float inv = select(ok, 1.0f, 0.0f) / select(ok, len, 1.0f);
    cx *= inv, cy *= inv, cz *= inv;
    const float sign = select(mask(cx * xc + cy * yc + cz * zc > 0), -1.0f, 1.0f);  // towards the camera
    nx[i] = sign * cx, ny[i] = sign * cy, nz[i] = sign * cz;
  }
}

// Normals by cross products of neighbours radius_cells away (thesis 3.2).
void raw_normals(const NormalsConfig& cfg, NormalGrid& g) {
  const int r = cfg.radius_cells;
  NormalGrid::Scratch& s = g.scratch;
  const RowPoints all{s.x.data(), s.y.data(), s.z.data(), s.iz.data()};
  const float jump = cfg.jump_ratio * 2 * r;
  // No normal within r of the border: rows above and below, columns left and right.
  const auto clear = [&](size_t from, size_t count) {
    for (float* v : {s.nx.data(), s.ny.data(), s.nz.data()}) std::fill(v + from, v + from + count, 0.0f);
  };
  const int w = g.width, h = g.height;
  if (2 * r >= w || 2 * r >= h) {
    clear(0, static_cast<size_t>(w) * h);
  } else {
    clear(0, static_cast<size_t>(r) * w);
    clear(static_cast<size_t>(h - r) * w, static_cast<size_t>(r) * w);
    for (int gy = r; gy < h - r; ++gy) {
      clear(static_cast<size_t>(gy) * w, r);
      clear(static_cast<size_t>(gy) * w + w - r, r);
    }
  }
  for (int gy = r; gy < g.height - r; ++gy) {
    const int c = g.index(r, gy);
    normals_row(all.at(c), all.at(c - r), all.at(c + r), all.at(c - r * g.width), all.at(c + r * g.width),
                g.width - 2 * r, jump, cfg.inverse_depth_kink_per_m, s.nx.data() + c, s.ny.data() + c,
                s.nz.data() + c);
  }
  for (size_t i = 0; i < g.normals.size(); ++i)
    g.has_normal[i] = s.nx[i] != 0.0f || s.ny[i] != 0.0f || s.nz[i] != 0.0f;
  if (!cfg.smooth)  // else smooth_normals writes them
    for (size_t i = 0; i < g.normals.size(); ++i) g.normals[i] = {s.nx[i], s.ny[i], s.nz[i]};
}

// 3x3 mean over neighbours on the same surface: noise down, edges kept. On
// struct-of-arrays copies, a row at a time (smooth_row), so the compiler runs
// four cells per instruction. A cell without a normal has a zero one (its dot
// is 0, never above cos_smooth) and adds nothing.
void smooth_normals(const NormalsConfig& cfg, NormalGrid& g) {
  const size_t n = g.normals.size();
  NormalGrid::Scratch& sc = g.scratch;
  for (auto* v : {&sc.sx, &sc.sy, &sc.sz}) v->assign(n, 0.0f);
  const float cos_smooth = std::cos(cfg.smooth_max_angle_deg * static_cast<float>(M_PI) / 180.0f);
  const float jump = cfg.jump_ratio * 2 * cfg.radius_cells;
  for (int gy = 1; gy < g.height - 1; ++gy)
    smooth_row(sc.nx.data(), sc.ny.data(), sc.nz.data(), sc.z.data(), gy * g.width + 1, g.width, g.width - 2,
               cos_smooth, jump, sc.sx.data(), sc.sy.data(), sc.sz.data());
  // Normalised in place, struct-of-arrays and selects so that it vectorises:
  // the same sums and division as Eigen's normalized() (x^2 + (y^2 + z^2),
  // then v / sqrt); zero where there is no normal.
  float* __restrict x = sc.sx.data();
  float* __restrict y = sc.sy.data();
  float* __restrict z = sc.sz.data();
  const uint8_t* has = g.has_normal.data();
  for (size_t i = 0; i < n; ++i) {
    const float sq = x[i] * x[i] + (y[i] * y[i] + z[i] * z[i]);
    const Mask on = mask(has[i] != 0) & mask(sq > 0.0f);
    const float len = select(on, std::sqrt(sq), 1.0f);
    x[i] = select(on, x[i] / len, 0.0f);
    y[i] = select(on, y[i] / len, 0.0f);
    z[i] = select(on, z[i] / len, 0.0f);
  }
  for (size_t i = 0; i < n; ++i) g.normals[i] = {x[i], y[i], z[i]};
}

}  // namespace

void compute_normals(const DepthImage& frame, const NormalsConfig& cfg, NormalGrid& g) {
  g.cell_px = grid_cell_px(cfg, frame.K.width);
  g.margin_cells = cfg.radius_cells;
  g.width = frame.K.width / g.cell_px;
  g.height = frame.K.height / g.cell_px;
  const size_t n = static_cast<size_t>(g.width) * g.height;
  // Sized, not cleared: cell_means writes every point, raw_normals every normal
  // (the border rows and columns it leaves out are cleared there).
  g.points.resize(n);
  g.normals.resize(n);
  for (auto* v : {&g.scratch.x, &g.scratch.y, &g.scratch.z, &g.scratch.iz, &g.scratch.nx, &g.scratch.ny, &g.scratch.nz})
    v->resize(n);
  g.has_point.resize(n);
  g.filled.resize(n);
  g.has_normal.resize(n);
  if (n == 0) return;
  switch (g.cell_px) {  // the common cell sides unrolled (grid_cell_px; 640 / 320 wide and Kinect v2)
    case 2: cell_means<2>(frame, cfg, g); break;
    case 3: cell_means<3>(frame, cfg, g); break;
    case 4: cell_means<4>(frame, cfg, g); break;
    default: cell_means<0>(frame, cfg, g);
  }
  raw_normals(cfg, g);
  if (cfg.smooth) smooth_normals(cfg, g);
}

}  // namespace stairs
