// Plane fits away from bridged surfaces (perception/bridged_surfaces.hpp): a
// riser grown together with the front face of its nosing slab, a few centimetres
// in front of it, tilts its least-squares plane; the cells' median normal finds
// the riser's.
#include "perception/bridged_surfaces.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace stairs {
namespace {

constexpr int kCols = 40, kRows = 20;

// A face 1.5 m ahead seen from the front (optical frame, y down), one cell per row of 1 cm:
// rows [0, slab_rows) the slab's front `overhang_m` nearer, one row across the slab's underside
// (normals turned 20 deg down by the normal kernel), the riser below. Each point carries a
// deterministic +-`noise_m` along the view.
NormalGrid riser_under_a_slab(int slab_rows, double overhang_m, double noise_m) {
  NormalGrid g;
  g.width = kCols, g.height = kRows;
  const int n = kCols * kRows;
  g.points.resize(n), g.normals.resize(n);
  g.has_point.assign(n, 1), g.has_normal.assign(n, 1), g.filled.assign(n, 1);
  const float tilt = 20.0f * static_cast<float>(M_PI) / 180.0f;
  for (int r = 0; r < kRows; ++r)
    for (int c = 0; c < kCols; ++c) {
      const int i = g.index(c, r);
      double z = 1.5;
      Eigen::Vector3f normal(0, 0, -1);
      if (r < slab_rows) {
        z -= overhang_m;
      } else if (r == slab_rows && slab_rows > 0) {
        z -= 0.5 * overhang_m;
        normal = Eigen::Vector3f(0, std::sin(tilt), -std::cos(tilt));
      }
      z += noise_m * (((c * 7 + r * 13) % 5) - 2) / 2.0;
      g.points[i] = Eigen::Vector3f(static_cast<float>(-0.2 + 0.01 * c), static_cast<float>(-0.05 + 0.01 * r),
                                    static_cast<float>(z));
      g.normals[i] = normal;
    }
  return g;
}

Segment whole(const NormalGrid& g) {
  Segment s;
  for (int i = 0; i < g.width * g.height; ++i) s.cells.push_back(i);
  fit_segment(g, s);
  return s;
}

double deg_from_facing(const Eigen::Vector3f& n) {
  return std::acos(std::min(1.0f, std::abs(n.z()))) * 180.0 / M_PI;
}

TEST(PerceptionBridgedSurfaces, ARiserGrownIntoItsNosingSlabKeepsTheRisersPlane) {
  const NormalGrid g = riser_under_a_slab(4, 0.03, 0.001);
  std::vector<Segment> segments = {whole(g)};
  const double before = deg_from_facing(segments[0].normal);
  ASSERT_GT(before, 3.0);  // the slab's 4 rows tilt the least-squares plane of 20
  const size_t cells = segments[0].cells.size();
  BridgedSurfacesScratch scratch;
  fit_away_from_bridged_surfaces(g, BridgedSurfacesConfig{}, segments, scratch);
  EXPECT_LT(deg_from_facing(segments[0].normal), 0.2) << "was " << before;
  EXPECT_NEAR(segments[0].centroid.z(), 1.5, 0.002);  // the riser's face, not between it and the slab
  EXPECT_EQ(segments[0].cells.size(), cells);         // the slab's front still belongs to the step's face
}

// A surface farther in front than a nosing slab's front (14 cm: another step's face) is no part of the
// plane's face: its cells leave the segment, and with them its extent.
TEST(PerceptionBridgedSurfaces, AFartherSurfaceGrownInLeavesTheSegment) {
  const NormalGrid g = riser_under_a_slab(4, 0.14, 0.001);
  std::vector<Segment> segments = {whole(g)};
  BridgedSurfacesScratch scratch;
  fit_away_from_bridged_surfaces(g, BridgedSurfacesConfig{}, segments, scratch);
  EXPECT_LT(deg_from_facing(segments[0].normal), 0.2);
  EXPECT_EQ(segments[0].cells.size(), static_cast<size_t>(kCols * (kRows - 5)));  // the face's rows only
  EXPECT_EQ(segments[0].sums.n, static_cast<double>(segments[0].cells.size()));
  for (int c : segments[0].cells) EXPECT_GT(g.points[c].z(), 1.49f);
}

// Cells behind the plane may be its own depth lengthened (time-of-flight multipath, a polished
// floor's reflections): a band 5 cm behind is no surface in front, and the fit stands.
TEST(PerceptionBridgedSurfaces, CellsBehindThePlaneAreNoBridgedSurface) {
  const NormalGrid g = riser_under_a_slab(4, -0.05, 0.001);
  std::vector<Segment> segments = {whole(g)};
  const Segment before = segments[0];
  ASSERT_GT(deg_from_facing(before.normal), 3.0);
  BridgedSurfacesScratch scratch;
  fit_away_from_bridged_surfaces(g, BridgedSurfacesConfig{}, segments, scratch);
  EXPECT_EQ(segments[0].normal, before.normal);
  EXPECT_EQ(segments[0].cells.size(), before.cells.size());
}

// Cells' normals 2 deg off their plane (a normal kernel's bias at range) over a noisy flat face with
// a speckle of cells 1.2 cm before it (one in 17): the cells off the median plane are its own noise, the
// rest no more than 1.4 times flatter, and the fit stands.
TEST(PerceptionBridgedSurfaces, ANoisyPlaneWhoseNormalsTurnKeepsItsFit) {
  NormalGrid g = riser_under_a_slab(0, 0.0, 0.004);
  const float tilt = 2.0f * static_cast<float>(M_PI) / 180.0f;
  for (Eigen::Vector3f& n : g.normals) n = Eigen::Vector3f(0, std::sin(tilt), -std::cos(tilt));
  for (size_t i = 0; i < g.points.size(); i += 17) g.points[i].z() -= 0.012f;  // in front: flying pixels
  std::vector<Segment> segments = {whole(g)};
  const Segment before = segments[0];
  BridgedSurfacesScratch scratch;
  fit_away_from_bridged_surfaces(g, BridgedSurfacesConfig{}, segments, scratch);
  EXPECT_EQ(segments[0].normal, before.normal);
  EXPECT_EQ(segments[0].rms_m, before.rms_m);
  // It is the flatness that decides: taking any trimmed fit would have moved it.
  BridgedSurfacesConfig any;
  any.min_flatter = 1.0f;
  fit_away_from_bridged_surfaces(g, any, segments, scratch);
  EXPECT_NE(segments[0].rms_m, before.rms_m);
}

}  // namespace
}  // namespace stairs
