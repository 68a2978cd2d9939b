// Normal-image edges (thesis 3.4.1) on clean synthetic stairs: convex edges
// at the nosings, concave ones at the riser feet, all horizontal and across
// the stair; nothing on a flat floor.
#include "perception/edges_normal_image.hpp"
#include "perception/normals.hpp"
#include "synthetic.hpp"

#include <gtest/gtest.h>

#include <cstdio>

namespace stairs {
namespace {

struct Expected {
  Eigen::Vector2d xz;  // forward, up (m): the renderer's edge, along y
  EdgeType type;
};

// The renderer's step edges (tests/perception/synthetic.hpp): riser k at
// x = first_riser + (k - 1) tread from z = -height + (k - 1) riser up to
// z = -height + k riser; the camera is the origin of its world frame, which
// is the gravity-aligned camera frame (roll turns about the optical axis).
std::vector<Expected> step_edges(double height_m, int steps, double first_riser_m, double riser_m, double tread_m) {
  std::vector<Expected> out;
  for (int k = 1; k <= steps; ++k) {
    const double x = first_riser_m + (k - 1) * tread_m;
    out.push_back({{x, -height_m + (k - 1) * riser_m}, EdgeType::Concave});
    out.push_back({{x, -height_m + k * riser_m}, EdgeType::Convex});
  }
  return out;
}

// Image row of a point at lateral position 0 (the renderer's intrinsics).
double image_row(const Eigen::Vector2d& xz, double pitch_deg, double roll_deg, int w) {
  const Eigen::Vector3d o = test::optical_to_world(pitch_deg, roll_deg).transpose() *
                            Eigen::Vector3d(xz.x(), 0.0, xz.y());
  const double f = 525.0 * w / 640;
  return f * o.y() / o.z() + (w * 3 / 4 - 1) / 2.0;
}

// Distance (m) of a point of the renderer's edges (which run along y) from
// an edge's line.
double xz_distance(const Edge& e, const Eigen::Vector2d& xz) {
  const Eigen::Vector3d a = e.start.cast<double>(), b = e.end.cast<double>();
  const Eigen::Vector3d u = (b - a).normalized();
  const Eigen::Vector3d d = Eigen::Vector3d(xz.x(), a.y(), xz.y()) - a;
  return (d - d.dot(u) * u).norm();
}

std::vector<Edge> edges_of(const DepthImage& img, double pitch_deg, double roll_deg, const PerceptionConfig& cfg) {
  NormalGrid grid;
  compute_normals(img, cfg.normals, grid);
  // The true gravity isolates this stage from the pose estimate.
  const Eigen::Matrix3f R = test::optical_to_world(pitch_deg, roll_deg).cast<float>();
  return normal_image_edges(grid, R, 0.0f, cfg.edges_normal_image, cfg.normals.grid_cell_px, cfg.stair.min_step_width_m);
}

TEST(PerceptionEdgesNormalImage, ConvexAtNosingsConcaveAtRiserFeet) {
  const double height = 1.0, first = 1.4, riser = 0.17, tread = 0.28;
  const int steps = 4;
  const PerceptionConfig cfg;
  for (const int w : {640, 320}) {
    for (const auto& [pitch, roll] : {std::pair{-30.0, 0.0}, std::pair{-35.0, 6.0}}) {
      const DepthImage img = test::render_stairs(w, w * 3 / 4, pitch, roll, height, steps, first, riser, tread);
      const std::vector<Edge> edges = edges_of(img, pitch, roll, cfg);
      const std::vector<Expected> truth = step_edges(height, steps, first, riser, tread);
      std::printf("%dx%d pitch %.0f roll %.0f: %zu edges\n", w, w * 3 / 4, pitch, roll, edges.size());
      for (const Edge& e : edges) {
        EXPECT_EQ(e.source, EdgeSource::NormalImage);
        const Eigen::Vector3f u = (e.end - e.start).normalized();
        EXPECT_LT(std::abs(u.z()), std::sin(5.0 * M_PI / 180));  // horizontal
        EXPECT_LT(std::abs(u.x()), std::sin(5.0 * M_PI / 180));  // across the stair axis (x)
        EXPECT_GE((e.end - e.start).norm(), cfg.stair.min_step_width_m);
        // Every edge lies on a real edge of its type.
        double best = 1e9;
        for (const Expected& t : truth)
          if (t.type == e.type) best = std::min(best, xz_distance(e, t.xz));
        EXPECT_LT(best, 0.03) << "edge at " << e.start.transpose() << " on no real "
                              << (e.type == EdgeType::Convex ? "nosing" : "riser foot");
      }
      // Every real edge well inside the image is found.
      for (const Expected& t : truth) {
        const double v = image_row(t.xz, pitch, roll, w);
        if (v < 0.1 * w * 3 / 4 || v > 0.9 * w * 3 / 4) continue;
        bool found = false;
        for (const Edge& e : edges) found |= e.type == t.type && xz_distance(e, t.xz) < 0.03;
        EXPECT_TRUE(found) << (t.type == EdgeType::Convex ? "nosing" : "riser foot") << " at x=" << t.xz.x()
                           << " z=" << t.xz.y() << " (row " << v << ") not found at " << w << " px, pitch " << pitch;
      }
    }
  }
}

TEST(PerceptionEdgesNormalImage, FlatFloorGivesNoEdges) {
  for (const int w : {640, 320})
    for (const double pitch : {-20.0, -45.0, -70.0}) {
      const DepthImage img = test::render_stairs(w, w * 3 / 4, pitch, 5.0, 1.0, 0);
      EXPECT_TRUE(edges_of(img, pitch, 5.0, PerceptionConfig{}).empty()) << w << " px, pitch " << pitch;
    }
}

}  // namespace
}  // namespace stairs
