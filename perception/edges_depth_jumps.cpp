#include "perception/edges_depth_jumps.hpp"

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/sample_consensus/ransac.h>
#include <pcl/sample_consensus/sac_model_line.h>

#include <algorithm>
#include <cmath>

namespace stairs {

namespace {

struct JumpPoint {
  Eigen::Vector3f q;  // gravity-aligned camera frame
  Eigen::Vector2f px;
};

// The near cells of jumps to a farther cell above them in the image, across at
// most cfg.gap_cells cells without a measurement (the projector's shadow).
std::vector<JumpPoint> jump_points(const NormalGrid& g, const Eigen::Matrix3f& R, const DepthJumpEdgesConfig& cfg) {
  std::vector<JumpPoint> out;
  const float half = 0.5f * static_cast<float>(g.cell_px);
  for (int gx = 0; gx < g.width; ++gx) {
    for (int gy = 1; gy < g.height; ++gy) {
      const int c = g.index(gx, gy);
      if (!g.has_point[c]) continue;
      int above = gy - 1;
      while (above >= 0 && gy - above <= cfg.gap_cells + 1 && !g.has_point[g.index(gx, above)]) --above;
      if (above < 0 || !g.has_point[g.index(gx, above)]) continue;
      const float zc = g.points[c].z(), zf = g.points[g.index(gx, above)].z();
      if (zf - zc < std::max(cfg.jump_min_m, cfg.jump_ratio * zc)) continue;
      out.push_back({R * g.points[c], {gx * g.cell_px + half, gy * g.cell_px + half}});
    }
  }
  return out;
}

}  // namespace

std::vector<JumpEdge> depth_jump_edges(const NormalGrid& g, const Eigen::Matrix3f& R, float yaw_rad,
                                       const DepthJumpEdgesConfig& cfg, float min_length_m) {
  std::vector<JumpPoint> pts = jump_points(g, R, cfg);
  std::sort(pts.begin(), pts.end(), [](const JumpPoint& a, const JumpPoint& b) { return a.q.z() < b.q.z(); });
  const float deg = static_cast<float>(M_PI) / 180.0f;
  const Eigen::Vector3f axis(std::cos(yaw_rad), std::sin(yaw_rad), 0.0f);
  const Eigen::Vector3f lateral(-axis.y(), axis.x(), 0.0f);
  std::vector<JumpEdge> edges;
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
      pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
      for (int i : left) cloud->push_back({pts[i].q.x(), pts[i].q.y(), pts[i].q.z()});
      // Fixed seed: the same frame gives the same edges.
      pcl::SampleConsensusModelLine<pcl::PointXYZ>::Ptr model(
          new pcl::SampleConsensusModelLine<pcl::PointXYZ>(cloud, false));
      pcl::RandomSampleConsensus<pcl::PointXYZ> ransac(model, cfg.ransac_threshold_m);
      ransac.setMaxIterations(cfg.ransac_iterations);
      if (!ransac.computeModel()) break;
      pcl::Indices inliers;
      ransac.getInliers(inliers);
      if (static_cast<int>(inliers.size()) < cfg.min_points) break;
      Eigen::VectorXf coef;
      ransac.getModelCoefficients(coef);
      const Eigen::Vector3f dir = coef.segment<3>(3).normalized();
      std::vector<int> line;
      for (auto k : inliers) line.push_back(left[static_cast<size_t>(k)]);
      std::sort(line.begin(), line.end());
      std::vector<int> rest;
      std::set_difference(left.begin(), left.end(), line.begin(), line.end(), std::back_inserter(rest));
      left.swap(rest);
      if (std::abs(dir.z()) > std::sin(cfg.max_tilt_deg * deg) ||
          std::abs(dir.dot(axis)) > std::sin(cfg.max_axis_deg * deg))
        continue;
      std::vector<float> ts, ss, zs;
      for (int i : line) {
        ts.push_back(lateral.dot(pts[i].q));
        ss.push_back(axis.dot(pts[i].q));
        zs.push_back(pts[i].q.z());
      }
      const auto [lo, hi] = std::minmax_element(ts.begin(), ts.end());
      if (*hi - *lo < min_length_m) continue;
      const size_t mid = ss.size() / 2;
      std::nth_element(ss.begin(), ss.begin() + mid, ss.end());
      std::nth_element(zs.begin(), zs.begin() + mid, zs.end());
      JumpEdge e;
      e.s = ss[mid];
      e.z = zs[mid];
      e.t_min = *lo;
      e.t_max = *hi;
      const JumpPoint& a = pts[line[static_cast<size_t>(lo - ts.begin())]];
      const JumpPoint& b = pts[line[static_cast<size_t>(hi - ts.begin())]];
      e.edge.type = EdgeType::Convex;
      e.edge.source = EdgeSource::DepthJump;
      e.edge.start = e.s * axis + e.t_min * lateral + e.z * Eigen::Vector3f::UnitZ();
      e.edge.end = e.s * axis + e.t_max * lateral + e.z * Eigen::Vector3f::UnitZ();
      e.edge.start_px = a.px;
      e.edge.end_px = b.px;
      e.edge.support = static_cast<int>(line.size());
      edges.push_back(e);
    }
  }
  std::sort(edges.begin(), edges.end(), [](const JumpEdge& a, const JumpEdge& b) { return a.z > b.z; });
  return edges;
}

}  // namespace stairs
