// Ray-cast geometry: the rasteriser hits the right face at the analytic depth.
#include "drivers/sim/furniture.hpp"
#include "drivers/sim/raster.hpp"
#include "drivers/sim/render.hpp"
#include "drivers/sim/trajectory.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

using namespace stairs;
using namespace stairs::sim;

namespace {

Intrinsics kinect() { return {640, 480, 525.0, 525.0, 319.5, 239.5}; }

// Brute force: nearest front-facing face hit by the ray (stair frame), exact.
std::pair<int, double> nearest_face(const Geometry& g, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  int best = -1;
  double best_t = std::numeric_limits<double>::infinity();
  for (size_t f = 0; f < g.faces.size(); ++f) {
    const Face& face = g.faces[f];
    const double nd = face.normal.dot(d);
    if (nd >= 0.0) continue;
    const double t = face.normal.dot(face.corners_m[0] - o) / nd;
    if (t <= 0.0 || t >= best_t) continue;
    const Eigen::Vector3d p = o + t * d;
    // Inside a convex polygon of either winding: all edge tests have one sign.
    bool any_pos = false, any_neg = false;
    for (int i = 0; i < 4; ++i) {
      const Eigen::Vector3d e = face.corners_m[(i + 1) % 4] - face.corners_m[i];
      if (e.norm() < 1e-12) continue;
      const double side = e.cross(p - face.corners_m[i]).dot(face.normal);
      any_pos |= side > 1e-9;
      any_neg |= side < -1e-9;
    }
    if (!(any_pos && any_neg)) best = static_cast<int>(f), best_t = t;
  }
  return {best, best_t};
}

}  // namespace

TEST(SimGeometry, RiserAheadAtAnalyticDepth) {
  const Scene s = make_preset("straight_up");
  Renderer r(s, kinect(), perfect_sensor(), 1);
  // Level camera 2 m before the first riser at 9 cm: the centre sees riser 0.
  const Eigen::Isometry3d T = camera_pose({-2.0, 0.0, 0.09}, 0.0, 0.0, 0.0);
  ZBuffer zb;
  rasterise(r.geometry(), T, r.intrinsics(), zb);
  const DepthImage img = r.render(T, 0, 0);
  for (int v = 236; v <= 243; ++v)
    for (int u = 300; u <= 340; ++u) {
      const size_t i = static_cast<size_t>(v) * 640 + u;
      ASSERT_GE(zb.id[i], 0);
      const Face& f = r.geometry().faces[static_cast<size_t>(zb.id[i])];
      EXPECT_EQ(f.part, FacePart::Riser);
      EXPECT_EQ(f.step, 0);
      EXPECT_EQ(img.depth[i], 2000);  // a plane facing the camera: z is the same everywhere
    }
}

// Open risers: a ray level with the gap between the first two slabs passes under the second one and
// meets what stands behind the flight (the landing's front face down to the floor), not a riser; a ray
// at the second slab's edge meets that step's "riser" (its front, the slab's 4 cm); under a slab lies
// the floor.
TEST(SimGeometry, OpenRisersShowWhatLiesBehindTheGaps) {
  const Scene s = make_preset("open_risers");
  ASSERT_TRUE(s.open_risers);
  const Geometry g = build_geometry(s);
  const std::vector<StepGeometry> steps = step_geometry(s);
  const StepGeometry& first = steps[0];
  const StepGeometry& second = steps[1];
  // Level, from 2 m before the flight, at the middle of the second step's gap (between the first slab's
  // top and the second slab's underside).
  const double gap_z = 0.5 * (first.top_z_m + second.top_z_m - s.nosing_thickness_m);
  auto [f, t] = nearest_face(g, {-2.0, 0.0, gap_z}, Eigen::Vector3d::UnitX());
  ASSERT_GE(f, 0);
  EXPECT_NE(g.faces[f].part, FacePart::Riser) << "a riser under an open step";
  EXPECT_GT(t, 2.0 + second.riser_x_m + 0.5) << "the ray stopped near the flight";
  // At the second slab's front, 1 cm below its top: the step's edge, labelled as its riser.
  std::tie(f, t) = nearest_face(g, {-2.0, 0.0, second.top_z_m - 0.01}, Eigen::Vector3d::UnitX());
  ASSERT_GE(f, 0);
  EXPECT_EQ(g.faces[f].part, FacePart::Riser);
  EXPECT_EQ(g.faces[f].step, 1);
  EXPECT_NEAR(t, 2.0 + second.riser_x_m, 1e-9);
  // Under the first slab: its underside above, the floor below.
  std::tie(f, t) = nearest_face(g, {0.5 * (first.riser_x_m + first.end_x_m), 0.0, 0.01}, Eigen::Vector3d::UnitZ());
  ASSERT_GE(f, 0);
  EXPECT_NEAR(t, first.top_z_m - s.nosing_thickness_m - 0.01, 1e-9) << "the slab's underside above the floor";
  std::tie(f, t) = nearest_face(g, {0.5 * (first.riser_x_m + first.end_x_m), 0.0, 0.01}, -Eigen::Vector3d::UnitZ());
  ASSERT_GE(f, 0);
  EXPECT_NEAR(t, 0.01, 1e-9) << "the floor beneath the flight";
}

// Furniture beside a flight: every piece of the family on the floor left of the flight, 0.3 m clear of
// it, ending 0.3 m before the first riser, the room wide enough for it; never through a wall or into a
// room without a stair.
TEST(SimGeometry, FurnitureBesideTheFlightStandsClearOfIt) {
  Scene s = make_preset("open_sides");
  const size_t before = s.boxes.size();
  furnish_beside_flight(s, "kitchen_table", 3);
  ASSERT_GT(s.boxes.size(), before + 10);  // a table and its chairs
  double y_max = 0.0;
  for (size_t i = before; i < s.boxes.size(); ++i) {
    const Box& b = s.boxes[i];
    EXPECT_GE(b.min_m.y(), 0.5 * s.width_m + 0.3 - 1e-9);
    EXPECT_LE(b.max_m.x(), -0.3 + 1e-9);
    EXPECT_GE(b.min_m.z(), 0.0);
    y_max = std::max(y_max, b.max_m.y());
  }
  EXPECT_LT(y_max, 0.5 * s.room_width_m);
  Scene walled = make_preset("straight_up");  // walls on both sides
  EXPECT_THROW(furnish_beside_flight(walled, "sofa", 1), std::invalid_argument);
  Scene room = make_preset("flat_room");
  EXPECT_THROW(furnish_beside_flight(room, "sofa", 1), std::invalid_argument);
  Scene open = make_preset("open_sides");
  EXPECT_THROW(furnish_beside_flight(open, "no_such_family", 1), std::invalid_argument);
}

TEST(SimGeometry, FloorDepthMatchesPlaneIntersection) {
  const Scene s = make_preset("straight_up");
  Renderer r(s, kinect(), perfect_sensor(), 1);
  const double h = 1.1;
  const Eigen::Isometry3d T = camera_pose({-4.0, 0.2, h}, 10.0, -40.0, 3.0);
  const DepthImage img = r.render(T, 0, 0);
  const Intrinsics K = r.intrinsics();
  int checked = 0;
  for (int v = 300; v < 480; v += 5)
    for (int u = 0; u < 640; u += 5) {
      const Eigen::Vector3d d = T.linear() * Eigen::Vector3d((u - K.cx) / K.fx, (v - K.cy) / K.fy, 1.0);
      const double z = -h / d.z();  // ray parameter = optical depth, as the ray's z is 1
      const Eigen::Vector3d p = T.translation() + z * d;
      if (p.x() > -0.1 || p.x() < -4.9 || std::abs(p.y()) > 0.5 || z > 4.4) continue;  // stay on the open floor
      EXPECT_NEAR(img.depth[static_cast<size_t>(v) * 640 + u] * 0.001, z, 0.0006) << u << "," << v;
      ++checked;
    }
  EXPECT_GT(checked, 500);
}

TEST(SimGeometry, RasteriserAgreesWithBruteForceRayCast) {
  for (const std::string name : {"straight_up", "nosing", "open_sides", "two_flights", "ramp", "flat_room"}) {
    const Scene s = make_preset(name);
    Renderer r(s, kinect(), perfect_sensor(), 1);
    const Intrinsics K = r.intrinsics();
    for (const Eigen::Isometry3d& T : {camera_pose({-1.2, 0.1, 1.0}, 5.0, -30.0, 2.0),
                                       camera_pose({0.6, -0.1, 1.3}, -8.0, -40.0, -3.0),
                                       camera_pose({3.3, 0.0, 2.8}, 180.0, -35.0, 1.0)}) {
      ZBuffer zb;
      rasterise(r.geometry(), T, K, zb);
      int total = 0, agree = 0;
      for (int v = 1; v < 480; v += 7)
        for (int u = 2; u < 640; u += 7) {
          const Eigen::Vector3d d = T.linear() * Eigen::Vector3d((u - K.cx) / K.fx, (v - K.cy) / K.fy, 1.0);
          const auto [face, t] = nearest_face(r.geometry(), T.translation(), d);
          const size_t i = static_cast<size_t>(v) * 640 + u;
          if (face < 0 && r.geometry().cylinders.empty()) {
            EXPECT_EQ(zb.id[i], -1) << name;
            continue;
          }
          ++total;
          if (zb.id[i] == face && std::abs(1.0 / zb.inv_z[i] - t) < 1e-4 * t) ++agree;
        }
      // Only pixels whose centre lies on a shared edge may differ.
      EXPECT_GE(agree, total - total / 200) << name;
    }
  }
}
