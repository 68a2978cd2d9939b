#include "perception/plane_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

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
  std::vector<int> out;
  for (;; ++stride) {
    out.clear();
    for (int c : cells)
      if ((c % g.width) % stride == 0 && (c / g.width) % stride == 0) out.push_back(c);
    if (static_cast<int>(out.size()) <= max_points) return out;
  }
}

namespace {

struct Group {
  std::vector<int> segs;
  Eigen::Vector3f normal = Eigen::Vector3f::Zero();  // gravity frame, support-weighted
  float key = 0;                                    // height or depth along the normal, m
  int support = 0;
  PlaneKind kind = PlaneKind::Other;
};

float percentile(std::vector<float>& v, float q) {
  const size_t k = std::min(v.size() - 1, static_cast<size_t>(q * (v.size() - 1)));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[k];
}

// Groups whose keys share a bin merge; then each group merges at most once with
// a group of the neighbouring bin whose key is closer than half a bin.
std::vector<Group> histogram_merge(std::vector<Group> items, float bin) {
  std::sort(items.begin(), items.end(), [](const Group& a, const Group& b) { return a.key < b.key; });
  std::vector<Group> out;
  std::vector<long> bins;
  std::vector<uint8_t> crossed;
  for (Group& g : items) {
    const long b = std::lround(std::floor(g.key / bin));
    bool merge = !out.empty() && bins.back() == b;
    if (!merge && !out.empty() && bins.back() == b - 1 && !crossed.back() &&
        std::abs(out.back().key - g.key) < 0.5f * bin) {
      merge = true;
      crossed.back() = 1;
    }
    if (merge) {
      Group& o = out.back();
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

}  // namespace

PlaneSet plane_geometry(const NormalGrid& g, const std::vector<Segment>& segments, const Eigen::Matrix3f& R,
                        const PerceptionConfig& cfg) {
  const float deg = static_cast<float>(M_PI) / 180.0f;
  const float cos_h = std::cos(cfg.horizontal_tol_deg * deg), sin_v = std::sin(cfg.vertical_tol_deg * deg);
  PlaneSet out;
  // Stair axis from the risers facing the camera (support-weighted).
  Eigen::Vector2f axis = Eigen::Vector2f::Zero();
  std::vector<Group> horizontal, vertical, other;
  for (size_t i = 0; i < segments.size(); ++i) {
    const Segment& s = segments[i];
    Group grp;
    grp.segs = {static_cast<int>(i)};
    grp.support = static_cast<int>(s.cells.size());
    grp.normal = (R * s.normal) * static_cast<float>(grp.support);
    const Eigen::Vector3f n = R * s.normal, c = R * s.centroid;
    if (n.z() > cos_h) {
      grp.key = c.z();
      horizontal.push_back(std::move(grp));
    } else if (std::abs(n.z()) < sin_v) {
      if (n.x() < -0.5f) axis += -n.head<2>().normalized() * static_cast<float>(grp.support);
      vertical.push_back(std::move(grp));
    } else {
      other.push_back(std::move(grp));
    }
  }
  out.yaw_rad = axis.squaredNorm() > 0 ? std::atan2(axis.y(), axis.x()) : 0.0f;
  const float cy = std::cos(out.yaw_rad), sy = std::sin(out.yaw_rad);

  horizontal = histogram_merge(std::move(horizontal), cfg.merge_bin_m);
  for (Group& grp : horizontal) grp.kind = PlaneKind::Tread;
  // Vertical planes: merged per normal direction (parallel within parallel_deg) by depth.
  std::vector<Group> merged_vertical;
  {
    const float cos_par = std::cos(cfg.parallel_deg * deg);
    std::vector<uint8_t> used(vertical.size(), 0);
    for (size_t i = 0; i < vertical.size(); ++i) {
      if (used[i]) continue;
      const Eigen::Vector3f ni = vertical[i].normal.normalized();
      std::vector<Group> family;
      for (size_t j = i; j < vertical.size(); ++j) {
        if (used[j] || vertical[j].normal.normalized().dot(ni) < cos_par) continue;
        used[j] = 1;
        Group v = vertical[j];
        const Segment& s = segments[v.segs[0]];
        v.key = -ni.dot(R * s.centroid);  // distance of the plane from the camera along its normal
        family.push_back(std::move(v));
      }
      for (Group& m : histogram_merge(std::move(family), cfg.merge_bin_m)) {
        const Eigen::Vector3f n = m.normal.normalized();
        m.kind = (n.x() * cy + n.y() * sy) < -std::cos(cfg.vertical_tol_deg * deg) ? PlaneKind::Riser
                                                                                     : PlaneKind::Other;
        merged_vertical.push_back(std::move(m));
      }
    }
  }
  std::vector<Group> all;
  for (auto* v : {&horizontal, &merged_vertical, &other})
    for (Group& grp : *v) all.push_back(std::move(grp));
  // Treads and risers first, then by support; capped.
  std::stable_sort(all.begin(), all.end(), [](const Group& a, const Group& b) {
    const bool sa = a.kind != PlaneKind::Other, sb = b.kind != PlaneKind::Other;
    return sa != sb ? sa : a.support > b.support;
  });
  if (static_cast<int>(all.size()) > cfg.max_planes) all.resize(cfg.max_planes);

  std::vector<float> ss, ts, zs, zs_all;
  std::vector<int> cells;
  for (const Group& grp : all) {
    cells.clear();
    for (int si : grp.segs) cells.insert(cells.end(), segments[si].cells.begin(), segments[si].cells.end());
    Plane p;
    p.kind = grp.kind;
    p.normal = grp.normal.normalized();
    p.support = static_cast<int>(cells.size()) * g.cell_px * g.cell_px;
    ss.clear();
    ts.clear();
    zs.clear();
    Eigen::Vector3f centroid = Eigen::Vector3f::Zero();
    for (int c : cells) {
      const Eigen::Vector3f q = R * g.points[c];
      centroid += q;
      ss.push_back(cy * q.x() + sy * q.y());
      ts.push_back(-sy * q.x() + cy * q.y());
      zs.push_back(q.z());
    }
    p.centroid = centroid / static_cast<float>(cells.size());
    zs_all = zs;
    PlaneExtent e;
    const float lo = cfg.extent_percentile, hi = 1.0f - cfg.extent_percentile;
    e.s_min = percentile(ss, lo);
    e.s_max = percentile(ss, hi);
    e.t_min = percentile(ts, lo);
    e.t_max = percentile(ts, hi);
    e.z_min = percentile(zs, lo);
    e.z_max = percentile(zs, hi);
    // Normals exist from normal_radius_cells inside the grid: a plane whose
    // top reaches the upper margin may continue above the view.
    const int margin = cfg.normal_radius_cells + 1;
    for (size_t k = 0; k < cells.size() && e.top_in_view; ++k)
      e.top_in_view = zs_all[k] < e.z_max - 0.02f || cells[k] / g.width > margin;
    for (size_t k = 0; k < cells.size() && e.bottom_in_view; ++k)
      e.bottom_in_view = zs_all[k] > e.z_min + 0.02f || cells[k] / g.width < g.height - 1 - margin;
    e.s_mean = cy * p.centroid.x() + sy * p.centroid.y();
    e.z_mean = p.centroid.z();
    const bool tread = p.kind == PlaneKind::Tread;
    if (tread) {
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
    const int cap = p.kind == PlaneKind::Other ? cfg.max_other_points : cfg.max_sample_points;
    for (int c : grid_subsample(g, cells, cap)) p.points.push_back(R * g.points[c]);
    out.planes.push_back(std::move(p));
    out.extents.push_back(e);
  }
  return out;
}

}  // namespace stairs
