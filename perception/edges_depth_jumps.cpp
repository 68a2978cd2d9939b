#include "perception/edges_depth_jumps.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>

namespace stairs {

namespace {

constexpr float kMinIncidence = 0.1f;  // cos of the ray's angle to the surface normal: below, ~84 deg, grazing

struct JumpPoint {
  Eigen::Vector3f q;       // gravity-aligned camera frame: the near cell's mean point
  Eigen::Vector3f nosing;  // the same, placed at the jump's pixel row (q where that fails)
  Eigen::Vector2f px;
};

// The near side of a jump: the plane through the near cell's point; a
// level one where the cell's normal is near up (a tread at its nosing: the
// cell's own normal bends across the edge).
struct NearSurface {
  Eigen::Vector3f p, n;  // optical frame
  // Where the ray through pixel (u, v) meets it (z = depth along the optical
  // axis); z <= 0 if it does not, at a grazing angle.
  Eigen::Vector3f point_at(const Intrinsics& K, float u, float v) const {
    const Eigen::Vector3f ray((u - K.cx) / K.fx, (v - K.cy) / K.fy, 1.0f);
    const float den = n.dot(ray);
    return std::abs(den) > kMinIncidence * ray.norm() ? ray * (n.dot(p) / den) : Eigen::Vector3f(0, 0, -1);
  }
};

// Where a jump runs through a near cell at pixel resolution: in each pixel
// column of the cell, the upper edge of the last pixel (going up the image)
// that the near surface explains, before one beyond the middle of the jump
// (pixels in between, the flying pixels of a time-of-flight sensor, are
// neither); the mean over the columns, or NaN. The cell's mean point lies
// inside its near part, about half a cell short of the nosing.
float jump_row_px(const DepthImage& f, const NearSurface& near, int u0, int cols, int v_bottom, int v_top,
                  float far_m, const DepthJumpEdgesConfig& cfg) {
  const float mid = 0.5f * (near.p.z() + far_m);
  float sum = 0.0f;
  int n = 0;
  for (int u = u0; u < std::min(u0 + cols, f.K.width); ++u) {
    int last_near = -1;
    for (int v = std::min(v_bottom, f.K.height - 1); v >= std::max(v_top, 0); --v) {
      const float d = f.metres(u, v);
      if (d <= 0.0f) continue;  // no measurement (the shadow): look further up
      if (d >= mid) {
        if (last_near >= 0) sum += static_cast<float>(last_near) - 0.5f, ++n;
        break;
      }
      const float expected = near.point_at(f.K, static_cast<float>(u), static_cast<float>(v)).z();
      if (std::abs(d - expected) <= cfg.row_tolerance_m + cfg.row_tolerance_per_m2 * expected * expected)
        last_near = v;
    }
  }
  return n > 0 ? sum / static_cast<float>(n) : std::nanf("");
}

// The near cells of jumps to a farther cell above them in the image, across at
// most cfg.gap_cells cells without a measurement (the projector's shadow);
// each also placed where the ray through the jump's pixel row meets the near
// surface (else at the cell's mean point).
std::vector<JumpPoint> jump_points(const NormalGrid& g, const DepthImage& f, const Eigen::Matrix3f& R,
                                   const DepthJumpEdgesConfig& cfg) {
  std::vector<JumpPoint> out;
  const float half = 0.5f * static_cast<float>(g.cell_px);
  const Eigen::Vector3f up = R.row(2).transpose();  // optical frame
  const float level_cos = std::cos(cfg.level_tol_deg * static_cast<float>(M_PI) / 180.0f);
  const float level_tan = std::tan(cfg.level_tol_deg * static_cast<float>(M_PI) / 180.0f);
  for (int gx = 0; gx < g.width; ++gx) {
    for (int gy = 1; gy < g.height; ++gy) {
      const int c = g.index(gx, gy);
      if (!g.has_point[c]) continue;
      int above = gy - 1;
      while (above >= 0 && gy - above <= cfg.gap_cells + 1 && !g.has_point[g.index(gx, above)]) --above;
      if (above < 0 || !g.has_point[g.index(gx, above)]) continue;
      const float zc = g.points[c].z(), zf = g.points[g.index(gx, above)].z();
      const float jump = std::max(cfg.jump_min_m, cfg.jump_ratio * zc);
      if (zf - zc < jump) continue;
      const Eigen::Vector3f& p = g.points[c];
      // A cell at the grid's border has no normal for the level test below;
      // the line to the cell under it tells a level (within level_tol_deg of
      // horizontal) from a riser's top. Seen from above, the ray past an edge
      // descends: beyond a level's edge it meets what lies below. A farther
      // cell on that level (within depth noise) or above it is the level
      // receding at a grazing angle, or a wall rising from it: no edge (a
      // robot's far floor at the image's top made a 3.4 m "tread").
      if (!g.has_normal[c] && gy + 1 < g.height && g.has_point[g.index(gx, gy + 1)]) {
        const float height = up.dot(p);
        const Eigen::Vector3f d = p - g.points[g.index(gx, gy + 1)];
        const float rise = std::abs(up.dot(d)), run = (d - up.dot(d) * up).norm();
        const bool on_a_level = rise < run * level_tan;
        const float noise = cfg.row_tolerance_m + cfg.row_tolerance_per_m2 * zc * zc;
        if (height < 0.0f && on_a_level && up.dot(g.points[g.index(gx, above)]) > height - noise) continue;
      }
      Eigen::Vector3f at_row = p;
      const Eigen::Vector2f px(gx * g.cell_px + half, gy * g.cell_px + half);
      if (g.has_normal[c]) {
        const bool level = std::abs(g.normals[c].dot(up)) > level_cos;
        const NearSurface near{p, level ? up : g.normals[c]};
        // A far floor seen at a grazing angle grows in depth by more than a
        // jump from one cell to the next, yet the far cell lies on the near
        // cell's level: no discontinuity, no nosing.
        if (level) {
          const float on_near = near.point_at(f.K, px.x(), above * g.cell_px + half).z();
          if (on_near > 0 && std::abs(zf - on_near) < jump) continue;
        }
        const float v = jump_row_px(f, near, gx * g.cell_px, g.cell_px, (gy + 1) * g.cell_px - 1, above * g.cell_px,
                                    zf, cfg);
        if (std::isfinite(v)) {
          const Eigen::Vector3f hit = near.point_at(f.K, px.x(), v);
          if (hit.z() > 0 && (hit - p).norm() < cfg.refine_max_m) at_row = hit;
        }
      }
      out.push_back({R * p, R * at_row, px});
    }
  }
  return out;
}

// The points of one height group, struct-of-arrays for the inlier counts.
struct GroupPoints {
  std::vector<float> x, y, z;
  void assign(const std::vector<JumpPoint>& pts, const std::vector<int>& which) {
    x.resize(which.size()), y.resize(which.size()), z.resize(which.size());
    for (size_t k = 0; k < which.size(); ++k)
      x[k] = pts[which[k]].q.x(), y[k] = pts[which[k]].q.y(), z[k] = pts[which[k]].q.z();
  }
  int size() const { return static_cast<int>(x.size()); }
};

struct Line3 {
  Eigen::Vector3f point, dir;  // dir unit
};

// Points within `threshold` of the line: squared distance |v|^2 - (v.d)^2.
int count_within(const GroupPoints& g, const Line3& l, float threshold, std::vector<int>* inliers = nullptr) {
  const float t2 = threshold * threshold;
  int count = 0;
  for (int i = 0; i < g.size(); ++i) {
    const float vx = g.x[i] - l.point.x(), vy = g.y[i] - l.point.y(), vz = g.z[i] - l.point.z();
    const float along = vx * l.dir.x() + vy * l.dir.y() + vz * l.dir.z();
    const bool in = vx * vx + vy * vy + vz * vz - along * along <= t2;
    count += in;
    if (inliers && in) inliers->push_back(i);
  }
  return count;
}

// RANSAC line through two drawn points, kept by inlier count, stopping once
// an outlier-free draw is 99 % likely (PCL's RandomSampleConsensus rule).
// Tight code rather than PCL's SampleConsensusModelLine: its inlier count was
// 18 % of a robot log's run (perf) and set the frame's p95. Fixed seed: the
// same frame gives the same edges.
std::optional<Line3> ransac_line(const GroupPoints& g, float threshold, int max_iterations) {
  uint64_t state = 0x9E3779B97F4A7C15ull;
  auto draw = [&]() {  // xorshift64*
    state ^= state >> 12, state ^= state << 25, state ^= state >> 27;
    return static_cast<int>(((state * 0x2545F4914F6CDD1Dull) >> 33) % static_cast<uint64_t>(g.size()));
  };
  std::optional<Line3> best;
  int best_count = 0;
  double needed = max_iterations;
  for (int it = 0, skipped = 0; it < needed && it <= max_iterations && skipped < 10 * max_iterations;) {
    const int a = draw(), b = draw();
    const Eigen::Vector3f pa(g.x[a], g.y[a], g.z[a]), pb(g.x[b], g.y[b], g.z[b]);
    const float len = (pb - pa).norm();
    if (!(len > 1e-6f)) {
      ++skipped;
      continue;
    }
    const Line3 l{pa, (pb - pa) / len};
    const int count = count_within(g, l, threshold);
    if (count > best_count) {
      best_count = count;
      best = l;
      const double w = static_cast<double>(count) / g.size();
      const double p_bad = std::clamp(1.0 - w * w, 1e-12, 1.0 - 1e-12);
      needed = std::log(1.0 - 0.99) / std::log(p_bad);
    }
    ++it;
  }
  return best;
}

// The line through the inliers' centroid along their principal direction:
// the best draw's line depends on which two points were drawn, this one on
// all its inliers (a far, noisy nosing comes out the same whatever the draw).
Line3 refit(const GroupPoints& g, const std::vector<int>& inliers) {
  Eigen::Vector3f mean = Eigen::Vector3f::Zero();
  for (int i : inliers) mean += Eigen::Vector3f(g.x[i], g.y[i], g.z[i]);
  mean /= static_cast<float>(inliers.size());
  Eigen::Matrix3f cov = Eigen::Matrix3f::Zero();
  for (int i : inliers) {
    const Eigen::Vector3f d = Eigen::Vector3f(g.x[i], g.y[i], g.z[i]) - mean;
    cov += d * d.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3f> es;
  es.computeDirect(cov);
  return {mean, es.eigenvectors().col(2).normalized()};
}

}  // namespace

std::vector<JumpEdge> depth_jump_edges(const NormalGrid& g, const DepthImage& frame, const Eigen::Matrix3f& R,
                                       float yaw_rad, const DepthJumpEdgesConfig& cfg, float min_length_m) {
  std::vector<JumpPoint> pts = jump_points(g, frame, R, cfg);
  std::sort(pts.begin(), pts.end(), [](const JumpPoint& a, const JumpPoint& b) { return a.q.z() < b.q.z(); });
  const float deg = static_cast<float>(M_PI) / 180.0f;
  const Eigen::Vector3f axis(std::cos(yaw_rad), std::sin(yaw_rad), 0.0f);
  const Eigen::Vector3f lateral(-axis.y(), axis.x(), 0.0f);
  std::vector<JumpEdge> edges;
  GroupPoints group;
  std::vector<int> inliers;
  // Nosings lie at distinct heights: groups of points whose heights chain
  // within edge_height_gap_m (spanning at most twice that: a room full of
  // edges must not chain into one group); each may hold a few lines (a
  // nosing and a wall's top edge at the same height).
  for (size_t begin = 0; begin < pts.size();) {
    size_t end = begin + 1;
    while (end < pts.size() && pts[end].q.z() - pts[end - 1].q.z() < cfg.height_gap_m &&
           pts[end].q.z() - pts[begin].q.z() < 2 * cfg.height_gap_m)
      ++end;
    std::vector<int> left(end - begin);
    for (size_t k = 0; k < left.size(); ++k) left[k] = static_cast<int>(begin + k);
    begin = end;
    for (int lines = 0; lines < cfg.max_lines_per_group && static_cast<int>(left.size()) >= cfg.min_points;
         ++lines) {
      group.assign(pts, left);
      const std::optional<Line3> fit = ransac_line(group, cfg.ransac_threshold_m, cfg.ransac_iterations);
      if (!fit) break;
      inliers.clear();
      count_within(group, *fit, cfg.ransac_threshold_m, &inliers);
      if (static_cast<int>(inliers.size()) < cfg.min_points) break;
      const Line3 line_fit = refit(group, inliers);
      inliers.clear();
      count_within(group, line_fit, cfg.ransac_threshold_m, &inliers);
      if (static_cast<int>(inliers.size()) < cfg.min_points) break;
      const Eigen::Vector3f dir = line_fit.dir;
      std::vector<int> line;
      for (int k : inliers) line.push_back(left[static_cast<size_t>(k)]);
      std::sort(line.begin(), line.end());
      std::vector<int> rest;
      std::set_difference(left.begin(), left.end(), line.begin(), line.end(), std::back_inserter(rest));
      left.swap(rest);
      if (std::abs(dir.z()) > std::sin(cfg.max_tilt_deg * deg) ||
          std::abs(dir.dot(axis)) > std::sin(cfg.max_axis_deg * deg))
        continue;
      std::vector<float> ts, ss, zs, ns;
      for (int i : line) {
        ts.push_back(lateral.dot(pts[i].q));
        ss.push_back(axis.dot(pts[i].q));
        zs.push_back(pts[i].q.z());
        ns.push_back(axis.dot(pts[i].nosing));
      }
      const auto [lo, hi] = std::minmax_element(ts.begin(), ts.end());
      if (*hi - *lo < min_length_m) continue;
      const size_t mid = ss.size() / 2;
      std::nth_element(ss.begin(), ss.begin() + mid, ss.end());
      std::nth_element(zs.begin(), zs.begin() + mid, zs.end());
      JumpEdge e;
      std::nth_element(ns.begin(), ns.begin() + mid, ns.end());
      e.s = ss[mid];
      e.nosing_s = ns[mid];
      e.z = zs[mid];
      e.t_min = *lo;
      e.t_max = *hi;
      e.across = dir.head<2>().normalized();
      const JumpPoint& a = pts[line[static_cast<size_t>(lo - ts.begin())]];
      const JumpPoint& b = pts[line[static_cast<size_t>(hi - ts.begin())]];
      e.edge.type = EdgeType::Convex;
      e.edge.source = EdgeSource::DepthJump;
      // Published at the jump's pixel rows, the nosing itself: the near cells' mean points lie about
      // 1 cm inside the tread (test_edges_depth_jumps), and the tracker places frames on these edges.
      e.edge.start = e.nosing_s * axis + e.t_min * lateral + e.z * Eigen::Vector3f::UnitZ();
      e.edge.end = e.nosing_s * axis + e.t_max * lateral + e.z * Eigen::Vector3f::UnitZ();
      e.edge.start_px = a.px;
      e.edge.end_px = b.px;
      e.edge.support = static_cast<int>(line.size());
      edges.push_back(e);
    }
  }
  std::sort(edges.begin(), edges.end(), [](const JumpEdge& a, const JumpEdge& b) { return a.z > b.z; });
  return edges;
}

std::optional<EdgeAxis> axis_from_edges(const std::vector<JumpEdge>& edges, float cluster_deg, float height_gap_m) {
  // The axis is each line's direction turned a quarter; doubled, its sign drops out.
  std::vector<Eigen::Vector2f> doubled;
  for (const JumpEdge& e : edges) {
    const Eigen::Vector2f a(e.across.y(), -e.across.x());
    doubled.push_back(static_cast<float>(e.edge.support) * Eigen::Vector2f(a.x() * a.x() - a.y() * a.y(), 2 * a.x() * a.y()));
  }
  // A flight's nosings are parallel: the lines within cluster_deg of the line with the most support
  // near it, a rail's or a wall's top edge along the flight is not one of them.
  const float cos_cluster = std::cos(2.0f * cluster_deg * static_cast<float>(M_PI) / 180.0f);
  auto near = [&](size_t i, size_t j) { return doubled[i].normalized().dot(doubled[j].normalized()) >= cos_cluster; };
  Eigen::Vector2f best = Eigen::Vector2f::Zero();
  size_t best_i = 0;
  for (size_t i = 0; i < doubled.size(); ++i) {
    Eigen::Vector2f sum = Eigen::Vector2f::Zero();
    for (size_t j = 0; j < doubled.size(); ++j)
      if (near(i, j)) sum += doubled[j];
    if (sum.squaredNorm() > best.squaredNorm()) best = sum, best_i = i;
  }
  if (best.squaredNorm() == 0.0f) return std::nullopt;
  // How many heights its lines lie at (a flight's nosings, a rise apart; lines of one height group
  // may be one edge broken).
  std::vector<float> zs;
  for (size_t j = 0; j < doubled.size(); ++j)
    if (near(best_i, j)) zs.push_back(edges[j].z);
  std::sort(zs.begin(), zs.end());
  int heights = 1;
  for (size_t k = 1; k < zs.size(); ++k) heights += zs[k] - zs[k - 1] > 2 * height_gap_m;
  return EdgeAxis{0.5f * std::atan2(best.y(), best.x()), heights};  // within 90 deg of forward
}

}  // namespace stairs
