#include "perception/region_growing.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>

namespace stairs {

void fit_plane(const PlaneSums& m, Segment& s) {
  const double inv_n = 1.0 / m.n;
  const Eigen::Vector3d mean = m.sum * inv_n;
  Eigen::Matrix3d cov;
  cov << m.xx, m.xy, m.xz, m.xy, m.yy, m.yz, m.xz, m.yz, m.zz;
  cov = cov * inv_n - mean * mean.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
  es.computeDirect(cov);
  Eigen::Vector3d n = es.eigenvectors().col(0);
  if (n.dot(mean) > 0) n = -n;
  s.centroid = mean.cast<float>();
  s.normal = n.normalized().cast<float>();
  s.rms_m = static_cast<float>(std::sqrt(std::max(0.0, es.eigenvalues()(0))));
  for (int k = 0; k < 2; ++k) {
    s.axis[k] = es.eigenvectors().col(k + 1).cast<float>();
    s.spread_m2[k] = static_cast<float>(es.eigenvalues()(k + 1));
  }
}

void fit_segment(const NormalGrid& g, Segment& s) {
  s.sums = PlaneSums{};
  for (int c : s.cells) s.sums.add(g.points[c]);
  fit_plane(s.sums, s);
}

namespace {

// The cells left, right, above and below cell c (-1 off the grid).
std::array<int, 4> four_neighbours(const NormalGrid& g, int c) {
  const int gx = c % g.width, gy = c / g.width;
  return {gx > 0 ? c - 1 : -1, gx + 1 < g.width ? c + 1 : -1, gy > 0 ? c - g.width : -1,
          gy + 1 < g.height ? c + g.width : -1};
}

// Whether cell c of segment `label` lies at a depth jump: a 4-neighbour with a point, of no segment
// or another, nearer or farther by more than jump_ratio of its depth.
bool at_depth_jump(const NormalGrid& g, const std::vector<int>& labels, int label, int c, float jump_ratio) {
  const float limit = jump_ratio * g.points[c].z();
  for (int k : four_neighbours(g, c))
    if (k >= 0 && labels[k] != label && g.has_point[k] && std::abs(g.points[k].z() - g.points[c].z()) > limit)
      return true;
  return false;
}

// The segment's plane from its cells away from depth jumps, where at least `min_cells` remain (else
// from all of them); its sums keep all its cells. A cell at a jump mixes the two surfaces: a
// time-of-flight camera reads pixels between them (flying pixels), and the cell's mean takes those
// within normals.jump_ratio of its nearest surface. On a strip between two jumps (a tread seen from
// above between its nosing and the level beyond, a riser seen from below) both edges move the same
// way round and tilt it: a Kinect v2's treads 1.5-3 m down a flight tilted 2-8 deg, the nearer ones
// most of all beside the floor they set the pitch by, 1.8-2.9 deg off, and the far steps came out
// a half rise off, false. The normal faces the way the cells' own normals do (`normal_sum`): a
// segment one row of cells wide is a line, any plane through it fits, and which way a least-squares
// normal faces the camera is a coin toss there (a real Kinect v2's first riser, seen from above).
void fit_segment_away_from_jumps(const NormalGrid& g, const std::vector<int>& labels, int label, float jump_ratio,
                                 size_t min_cells, const Eigen::Vector3f& normal_sum, Segment& s) {
  PlaneSums jumps;
  for (int c : s.cells) {
    s.sums.add(g.points[c]);
    if (jump_ratio > 0.0f && at_depth_jump(g, labels, label, c, jump_ratio)) jumps.add(g.points[c]);
  }
  const PlaneSums away = s.sums - jumps;
  fit_plane(away.n >= static_cast<double>(min_cells) ? away : s.sums, s);
  if (s.normal.dot(normal_sum) < 0.0f) s.normal = -s.normal;
}

}  // namespace

std::vector<Segment> grow_regions(const NormalGrid& g, const RegionGrowingConfig& cfg, int image_width,
                                  int image_height, std::vector<int>& labels) {
  const int n = g.width * g.height;
  labels.assign(n, -1);
  std::vector<Segment> segments;
  if (n == 0) return segments;
  const float cos_max = std::cos(cfg.angle_deg * static_cast<float>(M_PI) / 180.0f);
  const float cos_region = std::cos(cfg.region_angle_deg * static_cast<float>(M_PI) / 180.0f);
  const double min_px = cfg.min_plane_px_320 * (static_cast<double>(image_width) * image_height) / (320.0 * 240.0);
  const size_t min_cells = static_cast<size_t>(std::max(3.0, min_px / (g.cell_px * g.cell_px)));
  std::vector<int> stack;
  stack.reserve(n);
  std::vector<int> grown;
  grown.reserve(n);
  int next_label = 0;
  for (int seed = 0; seed < n; ++seed) {
    if (!g.has_normal[seed] || labels[seed] != -1) continue;
    const int label = next_label++;
    grown.clear();
    stack.clear();
    stack.push_back(seed);
    labels[seed] = label;
    Eigen::Vector3f normal_sum = Eigen::Vector3f::Zero();
    while (!stack.empty()) {
      const int c = stack.back();
      stack.pop_back();
      grown.push_back(c);
      normal_sum += g.normals[c];
      // Within region_angle of the mean normal: n.s >= cos |s|, squared (no root per cell).
      const float region_bound = cos_region * cos_region * normal_sum.squaredNorm();
      const Eigen::Vector3f& nc = g.normals[c];
      const Eigen::Vector3f& pc = g.points[c];
      const float tol = std::min(cfg.distance_m * pc.z() * pc.z(), cfg.max_distance_m) + cfg.distance_floor_m;
      for (int k : four_neighbours(g, c)) {
        if (k < 0 || labels[k] != -1 || !g.has_normal[k]) continue;
        const float to_mean = g.normals[k].dot(normal_sum);
        if (g.normals[k].dot(nc) < cos_max || to_mean < 0 || to_mean * to_mean < region_bound) continue;
        if (std::abs(nc.dot(g.points[k] - pc)) > tol) continue;
        labels[k] = label;
        stack.push_back(k);
      }
    }
    if (grown.size() < min_cells) {
      for (int c : grown) labels[c] = -2;  // visited, no plane
      --next_label;
      continue;
    }
    Segment s;
    s.cells = grown;
    fit_segment_away_from_jumps(g, labels, label, cfg.fit_jump_ratio, min_cells, normal_sum, s);
    segments.push_back(std::move(s));
  }
  for (int& l : labels)
    if (l == -2) l = -1;
  return segments;
}

}  // namespace stairs
