// Depth-jump edges (thesis 3.4.2) on a simulated descending flight with the
// Kinect v1 sensor model: the nosings below the camera, and nothing else.
#include "drivers/sim/render.hpp"
#include "drivers/sim/trajectory.hpp"
#include "perception/edges_depth_jumps.hpp"
#include "perception/gravity.hpp"
#include "tools/score.hpp"
#include "synthetic.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace stairs {
namespace {

TEST(PerceptionEdgesDepthJumps, NosingsOfADescendingFlight) {
  const sim::Scene scene = sim::make_preset("straight_down");
  const Intrinsics K{320, 240, 262.5, 262.5, 159.5, 119.5};
  sim::Renderer renderer(scene, K, sim::SensorModel{}, 3);
  sim::TrajectoryConfig tc = sim::trajectory_defaults(sim::Carrier::HandHeld);
  tc.descending = true;
  tc.fps = 10;
  const sim::Trajectory traj(scene, tc);
  const std::vector<Step> real = eval::real_steps(renderer.stair_truth());
  const PerceptionConfig cfg;
  int frames = 0, matched_edges = 0, edges_total = 0, visible_nosings = 0, found_nosings = 0;
  double cell_err_m = 0, row_err_m = 0;  // along the axis, of the edges on a nosing
  for (int i = 0; i < traj.frames(); i += 2) {
    const Eigen::Isometry3d pose = traj.pose(i);
    const DepthImage img = renderer.render(pose, static_cast<int64_t>(traj.time_s(i) * 1e6), i);
    const GroundTruthFrame truth = renderer.truth(pose, traj.time_s(i), img);
    if (truth.visible_steps.size() < 3) continue;
    ++frames;
    NormalGrid grid;
    compute_normals(img, cfg.normals, grid);
    // The true gravity isolates this stage from the pose estimate.
    const Eigen::Vector3f up = (pose.linear().transpose() * Eigen::Vector3d::UnitZ()).cast<float>();
    const Eigen::Matrix3f R = pose_from_up(up).gravity_rotation.toRotationMatrix().cast<float>();
    const std::vector<JumpEdge> edges = depth_jump_edges(grid, img, R, 0.0f, cfg.edges_depth_jumps, cfg.stair.min_step_width_m);
    // Recall over the visible steps; precision over every real nosing (a far
    // step with fewer than 500 valid pixels still has a real edge).
    std::vector<Eigen::Vector3d> nosings, all_nosings;
    for (int k : truth.visible_steps) nosings.push_back(eval::true_nosing_in_gravity_frame(real[k], truth, 0.0));
    for (const Step& r : real) all_nosings.push_back(eval::true_nosing_in_gravity_frame(r, truth, 0.0));
    for (const JumpEdge& e : edges) {
      ++edges_total;
      EXPECT_EQ(e.edge.source, EdgeSource::DepthJump);
      EXPECT_EQ(e.edge.type, EdgeType::Convex);
      EXPECT_GE(e.t_max - e.t_min, cfg.stair.min_step_width_m);
      // The observation's edge is the nosing itself, at the jump's pixel rows (yaw 0: the axis is x).
      EXPECT_NEAR(0.5f * (e.edge.start.x() + e.edge.end.x()), e.nosing_s, 1e-4f);
      for (const Eigen::Vector3d& n : all_nosings)
        if (std::abs(e.s - n.x()) < 0.04 && std::abs(e.z - n.z()) < 0.03) {
          ++matched_edges;
          cell_err_m += std::abs(e.s - n.x());
          row_err_m += std::abs(e.nosing_s - n.x());
          break;
        }
    }
    for (const Eigen::Vector3d& n : nosings) {
      ++visible_nosings;
      for (const JumpEdge& e : edges)
        if (std::abs(e.s - n.x()) < 0.04 && std::abs(e.z - n.z()) < 0.03) {
          ++found_nosings;
          break;
        }
    }
  }
  ASSERT_GE(frames, 10);
  std::printf("%d frames: %d of %d visible nosings found, %d of %d edges on a nosing, mean error along the axis "
              "%.2f cm (cells' mean points), %.2f cm (at the jump's pixel row)\n",
              frames, found_nosings, visible_nosings, matched_edges, edges_total, 100 * cell_err_m / matched_edges,
              100 * row_err_m / matched_edges);
  // Measured: 114 of 114 nosings, 136 of 136 edges. The nosing right below
  // the camera is no jump until it is passed.
  EXPECT_GE(matched_edges, 0.95 * edges_total);
  EXPECT_GE(found_nosings, 0.9 * visible_nosings);
  // The cells' mean points lie inside the tread, short of its nosing; placed
  // at the jump's pixel row the edge is the nosing. Measured 2026-12-02: 1.06
  // cm from the cells, 0.50 cm at the pixel row.
  EXPECT_LT(row_err_m, 0.6 * cell_err_m);
}

// A robot's camera 0.6 m above a plain floor, looking 15 deg down, depth to
// 4.5 m: far away the floor's depth grows by more than a jump from one cell
// to the next (a D435 at 3-5 m gave "nosings" there, and a 4 m "landing" past
// the bottom of a flight), yet each far cell lies on the near cell's level: no
// edge. Looking 33 deg down the floor reaches the image's top rows, whose
// cells have no normal (the grid's border): there too (a robot's D435 at the
// foot of a flight made a 3.4 m "tread" of it).
TEST(PerceptionEdgesDepthJumps, AFarFloorAtAGrazingAngleIsNoNosing) {
  for (const double pitch : {-15.0, -33.0}) {
    DepthImage img = test::render_stairs(640, 480, pitch, 0, 0.6, 0);
    for (uint16_t& d : img.depth)
      if (d > 4500) d = 0;
    const PerceptionConfig cfg;
    NormalGrid grid;
    compute_normals(img, cfg.normals, grid);
    const Eigen::Vector3f up = (test::optical_to_world(pitch, 0).transpose() * Eigen::Vector3d::UnitZ()).cast<float>();
    const Eigen::Matrix3f R = pose_from_up(up).gravity_rotation.toRotationMatrix().cast<float>();
    // The cells do jump by more than the threshold far away.
    int steep = 0, top_row_points = 0;
    for (int gy = 1; gy < grid.height; ++gy) {
      const int c = grid.index(grid.width / 2, gy), a = grid.index(grid.width / 2, gy - 1);
      if (grid.has_point[c] && grid.has_point[a] &&
          grid.points[a].z() - grid.points[c].z() >
              std::max(cfg.edges_depth_jumps.jump_min_m, cfg.edges_depth_jumps.jump_ratio * grid.points[c].z()))
        ++steep;
    }
    for (int gx = 0; gx < grid.width; ++gx) top_row_points += grid.has_point[grid.index(gx, 0)];
    ASSERT_GT(steep, 3) << pitch;
    if (pitch < -30) {
      ASSERT_GT(top_row_points, grid.width / 2) << "the floor reaches the top border";
    }
    EXPECT_TRUE(depth_jump_edges(grid, img, R, 0.0f, cfg.edges_depth_jumps, cfg.stair.min_step_width_m).empty())
        << pitch;
  }
}

// Looking down a flight turned 12 deg from it: the nosings' lines, either sign,
// give the stair axis 12 deg from forward, weighted by their support.
TEST(PerceptionEdgesDepthJumps, TheNosingsLinesGiveTheStairAxis) {
  const float turn = 12.0f * static_cast<float>(M_PI) / 180.0f;
  std::vector<JumpEdge> edges(3);
  edges[0].across = {-std::sin(turn), std::cos(turn)};
  edges[1].across = {std::sin(turn), -std::cos(turn)};
  edges[2].across = {0.0f, 1.0f};  // a short line across forward, little support
  edges[0].edge.support = 200, edges[1].edge.support = 200, edges[2].edge.support = 1;
  const auto axis = axis_from_edges(edges, 10.0f, 0.02f);
  ASSERT_TRUE(axis.has_value());
  EXPECT_NEAR(axis->yaw_rad, turn, 0.002f);
  EXPECT_FALSE(axis_from_edges({}, 10.0f, 0.02f).has_value());
}

// Looking down a flight 35 deg off its axis, the lines searched for the axis may include others (a
// table's or a wall's edge seen against what lies beyond): the nosings are parallel to each other
// and it is not, so the axis is theirs alone (a support-weighted mean of all was 14 deg off).
TEST(PerceptionEdgesDepthJumps, ALineAcrossOtherThanTheNosingsDoesNotTurnTheirAxis) {
  const float turn = 35.0f * static_cast<float>(M_PI) / 180.0f;
  std::vector<JumpEdge> edges(4);
  for (int k = 0; k < 3; ++k) {
    edges[k].across = {-std::sin(turn), std::cos(turn)};
    edges[k].edge.support = 100;
    edges[k].z = -0.17f * static_cast<float>(k);  // a rise apart
  }
  const float other = turn + 50.0f * static_cast<float>(M_PI) / 180.0f;
  edges[3].across = {-std::sin(other), std::cos(other)};  // 50 deg off the nosings
  edges[3].edge.support = 150;
  edges[3].z = -0.1f;
  const auto axis = axis_from_edges(edges, 10.0f, 0.02f);
  ASSERT_TRUE(axis.has_value());
  EXPECT_NEAR(axis->yaw_rad, turn, 0.002f);
  EXPECT_EQ(axis->heights, 3);  // the nosings' three
}

}  // namespace
}  // namespace stairs
