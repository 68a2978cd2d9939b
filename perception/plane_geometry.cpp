#include "perception/plane_geometry.hpp"

#include "common/median.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <optional>
#include <tuple>
#include <utility>

namespace stairs {

Eigen::Vector3f PlaneSet::to_camera(float s, float t, float z) const {
  const float c = std::cos(yaw_rad), sn = std::sin(yaw_rad);
  return {c * s - sn * t, sn * s + c * t, z};
}

float PlaneSet::axial(const Eigen::Vector3d& p) const {
  return std::cos(yaw_rad) * static_cast<float>(p.x()) + std::sin(yaw_rad) * static_cast<float>(p.y());
}

float PlaneSet::lateral(const Eigen::Vector3d& p) const {
  return -std::sin(yaw_rad) * static_cast<float>(p.x()) + std::cos(yaw_rad) * static_cast<float>(p.y());
}

std::vector<int> grid_subsample(const NormalGrid& g, const std::vector<int>& cells, int max_points) {
  if (static_cast<int>(cells.size()) <= max_points) return cells;
  int stride = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(cells.size()) / max_points)));
  // Which grid rows and columns each stride keeps, a table per stride: no
  // division per cell (two per cell and stride were 4 % of a frame).
  std::vector<uint8_t> on_row(static_cast<size_t>(g.height)), on_col(static_cast<size_t>(g.width));
  std::vector<int> out;
  for (;; ++stride) {
    for (int y = 0; y < g.height; ++y) on_row[y] = y % stride == 0;
    for (int x = 0; x < g.width; ++x) on_col[x] = x % stride == 0;
    out.clear();
    for (int c : cells) {
      const int gy = c / g.width;
      if (on_row[gy] && on_col[c - gy * g.width]) out.push_back(c);
    }
    if (static_cast<int>(out.size()) <= max_points) return out;
  }
}

namespace {

constexpr float kDeg = static_cast<float>(M_PI) / 180.0f;

struct Group {
  std::vector<int> segs;
  Eigen::Vector3f normal = Eigen::Vector3f::Zero();  // gravity frame, support-weighted
  float key = 0;                                    // height or depth along the normal, m
  int support = 0;
  PlaneKind kind = PlaneKind::Other;
  float s_lo = 0, s_hi = 0, t_lo = 0, t_hi = 0;      // treads: extent along and across the axis, m
};

// Buffers of trimmed_range, reused across calls.
struct RankScratch {
  std::vector<uint8_t> bucket_of;  // each value's histogram bucket
  std::vector<float> lo, hi;       // the values of the buckets holding the two ranks
};

// The q and 1-q percentiles (q <= 0.5) of v, whose range [lo, hi] the caller
// found, exactly, in two linear passes instead of two selections: a histogram
// of the values finds the bucket holding each rank, and only those buckets'
// values are selected among.
std::pair<float, float> trimmed_range(const std::vector<float>& v, float lo, float hi, float q, RankScratch& x) {
  const size_t n = v.size();
  if (!(hi > lo)) return {lo, hi};
  const auto rank = [&](float p) { return std::min(n - 1, static_cast<size_t>(p * (n - 1))); };
  const size_t ranks[2] = {rank(q), rank(1.0f - q)};
  constexpr int kBuckets = 256;
  const float scale = (kBuckets - 1) / (hi - lo);
  std::array<uint32_t, kBuckets> count{};
  x.bucket_of.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const int b = std::min(kBuckets - 1, static_cast<int>((v[i] - lo) * scale));
    x.bucket_of[i] = static_cast<uint8_t>(b);
    ++count[b];
  }
  int bucket[2];
  size_t below[2];
  for (int k = 0; k < 2; ++k) {
    below[k] = 0;
    bucket[k] = 0;
    while (below[k] + count[bucket[k]] <= ranks[k]) below[k] += count[bucket[k]++];
  }
  x.lo.clear();
  x.hi.clear();
  for (size_t i = 0; i < n; ++i) {
    if (x.bucket_of[i] == bucket[0]) x.lo.push_back(v[i]);
    if (x.bucket_of[i] == bucket[1]) x.hi.push_back(v[i]);
  }
  std::nth_element(x.lo.begin(), x.lo.begin() + (ranks[0] - below[0]), x.lo.end());
  std::nth_element(x.hi.begin(), x.hi.begin() + (ranks[1] - below[1]), x.hi.end());
  return {x.lo[ranks[0] - below[0]], x.hi[ranks[1] - below[1]]};
}

// Groups whose keys share a bin merge where `joinable` lets them; then each group merges at most
// once with a group of the neighbouring bin whose key is closer than half a bin.
template <class Joinable>
std::vector<Group> histogram_merge(std::vector<Group> items, float bin, Joinable joinable) {
  std::sort(items.begin(), items.end(), [](const Group& a, const Group& b) { return a.key < b.key; });
  std::vector<Group> out;
  std::vector<long> bins;
  std::vector<uint8_t> crossed;
  for (Group& g : items) {
    const long b = std::lround(std::floor(g.key / bin));
    long target = -1;  // a group of this bin it joins, the latest first
    for (long k = static_cast<long>(out.size()) - 1; k >= 0 && bins[k] == b && target < 0; --k)
      if (joinable(out[k], g)) target = k;
    if (target < 0 && !out.empty() && bins.back() == b - 1 && !crossed.back() &&
        std::abs(out.back().key - g.key) < 0.5f * bin && joinable(out.back(), g)) {
      target = static_cast<long>(out.size()) - 1;
      crossed.back() = 1;
    }
    if (target >= 0) {
      Group& o = out[static_cast<size_t>(target)];
      o.s_lo = std::min(o.s_lo, g.s_lo), o.s_hi = std::max(o.s_hi, g.s_hi);
      o.t_lo = std::min(o.t_lo, g.t_lo), o.t_hi = std::max(o.t_hi, g.t_hi);
      o.key = (o.key * o.support + g.key * g.support) / static_cast<float>(o.support + g.support);
      o.normal += g.normal;
      o.support += g.support;
      o.segs.insert(o.segs.end(), g.segs.begin(), g.segs.end());
    } else {
      out.push_back(std::move(g));
      bins.push_back(b);
      crossed.push_back(0);
    }
  }
  return out;
}

// Classification: treads (normal near up), vertical planes, others; the stair
// axis from the vertical ones facing the camera (axis_of) that are as wide
// as a tread (a flight's balusters, each a strip facing the camera, turned a descent's axis 14
// degrees and the tracker then misplaced the camera by up to 60 cm for 13 s; a person's body is
// strips of 0.2-0.3 m) and no taller than a rise; the taller ones' axis apart (walls, for the
// pipeline to fall back on).
struct Classified {
  std::vector<Group> horizontal, vertical, other;
  float yaw_rad = 0.0f;
  bool axis_from_risers = false;
  std::optional<float> tall_yaw_rad;
};

// A segment's size along the unit direction `d` (gravity frame; R: optical to gravity frame).
float size_along_m(const Segment& s, const Eigen::Matrix3f& R, const Eigen::Vector3f& d) {
  return s.size_along_m(R.transpose() * d);
}

// How wide a vertical segment is: its size along its horizontal in-plane direction.
float horizontal_width_m(const Segment& s, const Eigen::Matrix3f& R) {
  const Eigen::Vector3f h = Eigen::Vector3f::UnitZ().cross(R * s.normal);
  if (h.norm() < 1e-6f) return 0.0f;
  return size_along_m(s, R, h.normalized());
}

// A vertical plane facing the camera, wide enough to stand for the stair's axis.
struct Facing {
  Eigen::Vector2f dir;  // horizontal, unit: the way the plane faces away from the camera
  float offset_m;       // distance of the plane from the camera along dir
  int support;
};

// The stair axis from the planes facing the camera, support-weighted (thesis 3.5). A flight's
// risers are parallel planes a tread apart: where such a family is in view (two planes at least
// min_spacing_m apart along their normal), the axis is the best-supported family's alone, and a
// wall or a cabinet front seen at an angle beside it does not pull it (a walker 35 deg off the
// flight's axis saw the side wall as the biggest plane facing it: no riser was taken for one, and no
// step was found in any frame). Without such a family, all of them.
// The support-weighted sum of the chosen planes' directions; none without a plane.
std::optional<Eigen::Vector2f> axis_of(const std::vector<Facing>& facing, float parallel_deg, float min_spacing_m) {
  if (facing.empty()) return std::nullopt;
  const float cos_par = std::cos(parallel_deg * kDeg);
  Eigen::Vector2f all = Eigen::Vector2f::Zero(), best = Eigen::Vector2f::Zero();
  int best_support = 0;
  std::vector<float> offsets;
  for (const Facing& f : facing) {
    all += f.dir * static_cast<float>(f.support);
    Eigen::Vector2f sum = Eigen::Vector2f::Zero();
    int support = 0;
    offsets.clear();
    for (const Facing& g : facing)
      if (g.dir.dot(f.dir) >= cos_par) {
        sum += g.dir * static_cast<float>(g.support);
        support += g.support;
        offsets.push_back(g.offset_m);
      }
    const auto [lo, hi] = std::minmax_element(offsets.begin(), offsets.end());
    if (*hi - *lo >= min_spacing_m && support > best_support) best = sum, best_support = support;
  }
  return best_support > 0 ? best : all;
}

Classified classify(const std::vector<Segment>& segments, const Eigen::Matrix3f& R, const PlaneGeometryConfig& cfg) {
  const float cos_h = std::cos(cfg.horizontal_tol_deg * kDeg), sin_v = std::sin(cfg.vertical_tol_deg * kDeg);
  const float cos_facing = std::cos(cfg.axis_riser_max_deg * kDeg);
  Classified out;
  std::vector<Facing> facing, tall;
  for (size_t i = 0; i < segments.size(); ++i) {
    const Segment& s = segments[i];
    Group grp;
    grp.segs = {static_cast<int>(i)};
    grp.support = static_cast<int>(s.cells.size());
    grp.normal = (R * s.normal) * static_cast<float>(grp.support);
    const Eigen::Vector3f n = R * s.normal, c = R * s.centroid;
    // A surface shows only its front: an upward-facing one at or above the
    // camera's eye is seen from its back, so it is noise on a grazing patch
    // (or a misfit underside), never a tread.
    if (n.z() > cos_h && c.z() < 0) {
      grp.key = c.z();
      out.horizontal.push_back(std::move(grp));
    } else if (std::abs(n.z()) < sin_v) {
      if (n.x() < -cos_facing && horizontal_width_m(s, R) >= cfg.axis_riser_min_width_m) {
        const Eigen::Vector2f dir = -n.head<2>().normalized();
        const bool low = size_along_m(s, R, Eigen::Vector3f::UnitZ()) <= cfg.axis_riser_max_height_m;
        (low ? facing : tall).push_back({dir, dir.dot(c.head<2>()), grp.support});
      }
      out.vertical.push_back(std::move(grp));
    } else {
      out.other.push_back(std::move(grp));
    }
  }
  const auto axis = axis_of(facing, cfg.parallel_deg, cfg.axis_riser_min_spacing_m);
  out.axis_from_risers = axis.has_value();
  out.yaw_rad = axis ? std::atan2(axis->y(), axis->x()) : 0.0f;
  if (const auto wall = axis_of(tall, cfg.parallel_deg, cfg.axis_riser_min_spacing_m))
    out.tall_yaw_rad = std::atan2(wall->y(), wall->x());
  return out;
}

// Merging: treads by height; vertical planes per normal direction (parallel
// within cfg.parallel_deg) by depth along it, the ones facing the camera along
// the axis become risers. Treads and risers first, then by support; capped.
std::vector<Group> merge(Classified c, const NormalGrid& g, const std::vector<Segment>& segments,
                         const Eigen::Matrix3f& R, const PlaneGeometryConfig& cfg, int max_planes) {
  const float cy = std::cos(c.yaw_rad), sy = std::sin(c.yaw_rad);
  // Each tread piece's extent along (s) and across (t) the axis, over its cells.
  const Eigen::Vector3f along(cy, sy, 0.0f), across(-sy, cy, 0.0f);
  auto st = [&](int cell) {
    const Eigen::Vector3f q = R * g.points[cell];
    return Eigen::Vector2f(q.dot(along), q.dot(across));
  };
  for (Group& grp : c.horizontal) {
    grp.s_lo = grp.t_lo = std::numeric_limits<float>::infinity();
    grp.s_hi = grp.t_hi = -std::numeric_limits<float>::infinity();
    for (int cell : segments[grp.segs[0]].cells) {
      const Eigen::Vector2f p = st(cell);
      const float sq = p.x(), tq = p.y();
      grp.s_lo = std::min(grp.s_lo, sq), grp.s_hi = std::max(grp.s_hi, sq);
      grp.t_lo = std::min(grp.t_lo, tq), grp.t_hi = std::max(grp.t_hi, tq);
    }
  }
  // Pieces at one height are one surface unless a lower one is seen between them along the axis,
  // across at least tread_split_min_seen_fraction of their common width: nothing is seen through a
  // surface (a box's top before a flight, at its first tread's height, made one 2.1 m "landing" of
  // both, and the first step was lost with 8 false model steps).
  const std::vector<Group> pieces = c.horizontal;
  auto joinable = [&](const Group& a, const Group& b) {
    const float gap_lo = std::min(a.s_hi, b.s_hi), gap_hi = std::max(a.s_lo, b.s_lo);
    if (gap_lo >= gap_hi) return true;  // they overlap along the axis
    float t0 = std::max(a.t_lo, b.t_lo), t1 = std::min(a.t_hi, b.t_hi);
    if (t1 <= t0) t0 = std::min(a.t_lo, b.t_lo), t1 = std::max(a.t_hi, b.t_hi);  // side by side: the whole span
    const float below = std::min(a.key, b.key) - cfg.merge_bin_m;
    for (const Group& l : pieces) {
      if (l.key >= below || l.s_hi <= gap_lo || l.s_lo >= gap_hi || l.t_hi <= t0 || l.t_lo >= t1) continue;
      float lo = std::numeric_limits<float>::infinity(), hi = -lo;  // its cells' lateral span in the strip between
      for (int cell : segments[l.segs[0]].cells) {
        const Eigen::Vector2f p = st(cell);
        const float sq = p.x(), tq = p.y();
        if (sq > gap_lo && sq < gap_hi && tq > t0 && tq < t1) lo = std::min(lo, tq), hi = std::max(hi, tq);
      }
      if (hi - lo >= cfg.tread_split_min_seen_fraction * (t1 - t0)) return false;
    }
    return true;
  };
  std::vector<Group> all = histogram_merge(std::move(c.horizontal), cfg.merge_bin_m, joinable);
  for (Group& grp : all) grp.kind = PlaneKind::Tread;
  const float cos_par = std::cos(cfg.parallel_deg * kDeg), cos_riser = std::cos(cfg.vertical_tol_deg * kDeg);
  std::vector<uint8_t> used(c.vertical.size(), 0);
  for (size_t i = 0; i < c.vertical.size(); ++i) {
    if (used[i]) continue;
    const Eigen::Vector3f ni = c.vertical[i].normal.normalized();
    std::vector<Group> family;
    for (size_t j = i; j < c.vertical.size(); ++j) {
      if (used[j] || c.vertical[j].normal.normalized().dot(ni) < cos_par) continue;
      used[j] = 1;
      Group v = c.vertical[j];
      v.key = -ni.dot(R * segments[v.segs[0]].centroid);  // distance of the plane from the camera along its normal
      family.push_back(std::move(v));
    }
    for (Group& m : histogram_merge(std::move(family), cfg.merge_bin_m, [](const Group&, const Group&) { return true; })) {
      const Eigen::Vector3f n = m.normal.normalized();
      m.kind = (n.x() * cy + n.y() * sy) < -cos_riser ? PlaneKind::Riser : PlaneKind::Other;
      all.push_back(std::move(m));
    }
  }
  for (Group& grp : c.other) all.push_back(std::move(grp));
  std::stable_sort(all.begin(), all.end(), [](const Group& a, const Group& b) {
    const bool sa = a.kind != PlaneKind::Other, sb = b.kind != PlaneKind::Other;
    return sa != sb ? sa : a.support > b.support;
  });
  if (static_cast<int>(all.size()) > max_planes) all.resize(max_planes);
  return all;
}

// Whether the first cell with a point in the two above `cell` is nearer than it by more than gap_m.
bool nearer_just_above(const NormalGrid& g, int cell, float gap_m) {
  for (int up = 1; up <= 2; ++up) {
    const int c = cell - up * g.width;
    if (c < 0) return false;
    if (g.has_point[static_cast<size_t>(c)]) return g.points[c].z() < g.points[cell].z() - gap_m;
  }
  return false;
}

// Scratch buffers of extents(), reused across planes.
struct ExtentScratch {
  std::vector<float> ss, ts, zs, face;
  RankScratch ranks;
};

// A tread's strips of about strip_m across [t_min, t_max], from all its cells.
Strips strips_of(const std::vector<float>& ss, const std::vector<float>& ts, float t_min, float t_max, float strip_m) {
  Strips out;
  const float width = t_max - t_min;
  if (!(width > 0) || ss.empty()) return out;
  const int n = std::min(Strips::kMax, std::max(1, static_cast<int>(std::ceil(width / strip_m))));
  out.t0 = t_min;
  out.width = width / static_cast<float>(n);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  out.s_min.assign(static_cast<size_t>(n), nan);
  out.s_max.assign(static_cast<size_t>(n), nan);
  const float inv = 1.0f / out.width;
  for (size_t k = 0; k < ss.size(); ++k) {
    const float f = (ts[k] - t_min) * inv;
    if (!(f >= 0) || f >= static_cast<float>(n)) continue;
    const size_t i = static_cast<size_t>(f);
    if (!(ss[k] >= out.s_min[i])) out.s_min[i] = ss[k];  // NaN compares false: the first cell sets it
    if (!(ss[k] <= out.s_max[i])) out.s_max[i] = ss[k];
  }
  return out;
}

// Extents along the axis (s), across it (t) and up (z), trimmed percentiles;
// whether the plane's top / bottom rows are inside the grid's valid margin.
PlaneExtent extents(const NormalGrid& g, const std::vector<int>& cells, const Eigen::Matrix3f& R, float yaw_rad,
                    PlaneKind kind, const PlaneGeometryConfig& cfg, Eigen::Vector3f& centroid, ExtentScratch& x) {
  const bool face_band = kind == PlaneKind::Riser;
  const float cy = std::cos(yaw_rad), sy = std::sin(yaw_rad);
  x.ss.clear();
  x.ts.clear();
  x.zs.clear();
  centroid = Eigen::Vector3f::Zero();
  constexpr float kInf = std::numeric_limits<float>::infinity();
  float lo[3] = {kInf, kInf, kInf}, hi[3] = {-kInf, -kInf, -kInf};  // s, t, z ranges, found on the way
  for (int c : cells) {
    const Eigen::Vector3f q = R * g.points[c];
    centroid += q;
    const float st[3] = {cy * q.x() + sy * q.y(), -sy * q.x() + cy * q.y(), q.z()};
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], st[k]), hi[k] = std::max(hi[k], st[k]);
    x.ss.push_back(st[0]);
    x.ts.push_back(st[1]);
    x.zs.push_back(st[2]);
  }
  centroid /= static_cast<float>(cells.size());
  PlaneExtent e;
  std::tie(e.s_min, e.s_max) = trimmed_range(x.ss, lo[0], hi[0], cfg.extent_percentile, x.ranks);
  std::tie(e.t_min, e.t_max) = trimmed_range(x.ts, lo[1], hi[1], cfg.extent_percentile, x.ranks);
  std::tie(e.z_min, e.z_max) = trimmed_range(x.zs, lo[2], hi[2], cfg.extent_percentile, x.ranks);
  if (kind == PlaneKind::Tread) e.strips = strips_of(x.ss, x.ts, e.t_min, e.t_max, cfg.tread_strip_m);
  // Normals exist from margin_cells inside the grid: a plane whose top
  // reaches the upper margin may continue above the view.
  // Rows by index bounds: row > margin is index >= (margin + 1) * width (no division per cell).
  const int margin = g.margin_cells + 1;
  const int below_top = (margin + 1) * g.width, above_bottom = (g.height - 1 - margin) * g.width;
  // Nor is a riser's top in view where a nearer surface stands just above it in the image: the view of
  // it stops there (a table's far edge before a sofa's front made a 0.23 m "riser" and a false step).
  // Above a real riser's top lies its tread or the next riser, both farther.
  int top_cells = 0, hidden = 0;
  for (size_t k = 0; k < cells.size() && e.top_in_view; ++k) {
    if (x.zs[k] < e.z_max - cfg.view_edge_band_m) continue;
    e.top_in_view = cells[k] >= below_top;
    ++top_cells;
    if (face_band) hidden += nearer_just_above(g, cells[k], cfg.occluder_min_gap_m);
  }
  if (face_band && e.top_in_view) e.top_in_view = hidden <= cfg.occluded_top_fraction * top_cells;
  // Nor is its bottom in view where the depth below it ends (a time-of-flight
  // sensor's minimum range, dropout): the plane is cut there, not ended (a
  // robot's Kinect v2 measured an 8 cm first rise from a riser whose lower
  // half lay nearer than 0.5 m).
  for (size_t k = 0; k < cells.size() && e.bottom_in_view; ++k)
    e.bottom_in_view = x.zs[k] > e.z_min + cfg.view_edge_band_m ||
                       (cells[k] < above_bottom && g.has_point[static_cast<size_t>(cells[k] + g.width)]);
  e.s_mean = cy * centroid.x() + sy * centroid.y();
  e.z_mean = centroid.z();
  // A riser's face: the median position of its middle rows. Under a nosing overhang the slab's
  // front stands before the face at its top, and a concave foot reads long on a time-of-flight
  // camera; the mean of all its cells moved with how much of each the view held.
  if (face_band) {
    const float band = cfg.riser_face_band_fraction * (e.z_max - e.z_min);
    x.face.clear();
    for (size_t k = 0; k < cells.size(); ++k)
      if (x.zs[k] >= e.z_min + band && x.zs[k] <= e.z_max - band) x.face.push_back(x.ss[k]);
    if (x.face.size() >= 3) e.s_mean = median_in_place(x.face);
  }
  return e;
}

}  // namespace

PlaneSet plane_geometry(const NormalGrid& g, const std::vector<Segment>& segments, const Eigen::Matrix3f& R,
                        const PlaneGeometryConfig& cfg, const OutputConfig& caps, std::optional<float> axis_yaw_rad) {
  Classified classified = classify(segments, R, cfg);
  if (axis_yaw_rad) classified.yaw_rad = *axis_yaw_rad, classified.axis_from_risers = false;
  PlaneSet out;
  out.yaw_rad = classified.yaw_rad;
  out.axis_from_risers = classified.axis_from_risers;
  out.tall_facing_yaw_rad = classified.tall_yaw_rad;
  ExtentScratch scratch;
  std::vector<int> cells;
  for (const Group& grp : merge(std::move(classified), g, segments, R, cfg, caps.max_planes)) {
    cells.clear();
    for (int si : grp.segs) cells.insert(cells.end(), segments[si].cells.begin(), segments[si].cells.end());
    Plane p;
    p.kind = grp.kind;
    p.normal = grp.normal.normalized();
    p.support = static_cast<int>(cells.size()) * g.cell_px * g.cell_px;
    PlaneExtent e = extents(g, cells, R, out.yaw_rad, p.kind, cfg, p.centroid, scratch);
    if (p.kind == PlaneKind::Tread) {
      p.corners[Plane::kTopLeft] = out.to_camera(e.s_max, e.t_max, e.z_mean);
      p.corners[Plane::kTopRight] = out.to_camera(e.s_max, e.t_min, e.z_mean);
      p.corners[Plane::kBottomLeft] = out.to_camera(e.s_min, e.t_max, e.z_mean);
      p.corners[Plane::kBottomRight] = out.to_camera(e.s_min, e.t_min, e.z_mean);
      p.extent_m = e.s_max - e.s_min;
    } else {
      p.corners[Plane::kTopLeft] = out.to_camera(e.s_mean, e.t_max, e.z_max);
      p.corners[Plane::kTopRight] = out.to_camera(e.s_mean, e.t_min, e.z_max);
      p.corners[Plane::kBottomLeft] = out.to_camera(e.s_mean, e.t_max, e.z_min);
      p.corners[Plane::kBottomRight] = out.to_camera(e.s_mean, e.t_min, e.z_min);
      p.extent_m = e.z_max - e.z_min;
    }
    p.length_m = e.t_max - e.t_min;
    const int cap = p.kind == PlaneKind::Other ? caps.max_other_points : caps.max_sample_points;
    for (int c : grid_subsample(g, cells, cap)) p.points.push_back(R * g.points[c]);
    out.planes.push_back(std::move(p));
    out.extents.push_back(std::move(e));
  }
  return out;
}

std::optional<std::pair<float, float>> Strips::across(float t_lo, float t_hi) const {
  std::array<float, kMax> lo{}, hi{};
  size_t n = 0;
  for (size_t k = 0; k < s_min.size(); ++k) {
    const float mid = t0 + (static_cast<float>(k) + 0.5f) * width;
    if (mid < t_lo || mid > t_hi || std::isnan(s_min[k])) continue;
    lo[n] = s_min[k];
    hi[n++] = s_max[k];
  }
  if (n == 0) return std::nullopt;
  std::nth_element(lo.begin(), lo.begin() + n / 2, lo.begin() + n);
  std::nth_element(hi.begin(), hi.begin() + n / 2, hi.begin() + n);
  return std::make_pair(lo[n / 2], hi[n / 2]);
}

}  // namespace stairs
