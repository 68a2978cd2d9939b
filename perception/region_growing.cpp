#include "perception/region_growing.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
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
      const int gx = c % g.width, gy = c / g.width;
      const Eigen::Vector3f& nc = g.normals[c];
      const Eigen::Vector3f& pc = g.points[c];
      const float tol = std::min(cfg.distance_m * pc.z() * pc.z(), cfg.max_distance_m) + cfg.distance_floor_m;
      const int nb[4] = {gx > 0 ? c - 1 : -1, gx + 1 < g.width ? c + 1 : -1, gy > 0 ? c - g.width : -1,
                         gy + 1 < g.height ? c + g.width : -1};
      for (int k : nb) {
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
    fit_segment(g, s);
    segments.push_back(std::move(s));
  }
  for (int& l : labels)
    if (l == -2) l = -1;
  return segments;
}

}  // namespace stairs
