// The nosing overhang from a riser plane's points (tracker/nosing_overhang.hpp):
// the slab's front face at a riser's top against the face below it.
#include "tracker/config.hpp"
#include "tracker/nosing_overhang.hpp"

#include <gtest/gtest.h>

using namespace stairs;

namespace {

// A riser facing -x at x = face_m, seen from z_lo up to the nosing at z = 0.2 m, with a slab of
// `slab_m` thickness standing `overhang_m` before it; points every 5 mm, 20 across.
Plane riser(double face_m, double overhang_m, double slab_m, double z_lo = 0.0) {
  Plane p;
  p.kind = PlaneKind::Riser;
  for (double z = z_lo; z <= 0.2 + 1e-9; z += 0.005)
    for (int k = 0; k < 20; ++k)
      p.points.emplace_back(static_cast<float>(z > 0.2 - slab_m ? face_m - overhang_m : face_m),
                            static_cast<float>(0.05 * k), static_cast<float>(z));
  return p;
}

}  // namespace

TEST(NosingOverhang, TheSlabBeforeARisersFaceIsTheOverhang) {
  const OverhangConfig c;
  const Eigen::Isometry3d identity = Eigen::Isometry3d::Identity();
  ASSERT_TRUE(riser_overhang_m(riser(1.0, 0.03, 0.04), identity, 0.2, c));
  EXPECT_NEAR(*riser_overhang_m(riser(1.0, 0.03, 0.04), identity, 0.2, c), 0.03, 1e-6);
  EXPECT_NEAR(*riser_overhang_m(riser(1.0, 0.0, 0.04), identity, 0.2, c), 0.0, 1e-6) << "a plain riser";
  // In the model frame: the plane's points are taken there first.
  Eigen::Isometry3d shifted = Eigen::Isometry3d::Identity();
  shifted.translation() = Eigen::Vector3d(0.5, 0.0, 0.3);
  EXPECT_NEAR(*riser_overhang_m(riser(1.0, 0.025, 0.04), shifted, 0.5, c), 0.025, 1e-6);
  // The slab must be in view: a riser whose top is cut below the nosing says nothing of it.
  EXPECT_FALSE(riser_overhang_m(riser(1.0, 0.03, 0.04), identity, 0.3, c));
  // Nor does a sliver of a riser.
  EXPECT_FALSE(riser_overhang_m(riser(1.0, 0.03, 0.04, 0.15), identity, 0.2, c));
}

TEST(NosingOverhang, TheFlightsOverhangIsItsStepsMedianWithinDinsBound) {
  const OverhangConfig c;
  StairMap map;
  map.steps.resize(4);
  EXPECT_EQ(flight_overhang_m(map, c), 0.0) << "no riser measured: nosings as seen";
  map.steps[0].overhang_m.add(0.028, 30);
  EXPECT_EQ(flight_overhang_m(map, c), 0.0) << "one step is no flight's evidence";
  map.steps[1].overhang_m.add(0.031, 30);
  map.steps[2].overhang_m.add(0.2, 30);  // an outlier does not move the median
  EXPECT_NEAR(flight_overhang_m(map, c), 0.031, 1e-9);
  map.steps[3].overhang_m.add(-0.01, 30);
  map.steps[0].overhang_m = {};
  map.steps[1].overhang_m = {};
  map.steps[1].overhang_m.add(-0.02, 30);
  EXPECT_EQ(flight_overhang_m(map, c), 0.0) << "clamped: a nosing never stands behind its riser";
  StairMap wide;
  wide.steps.resize(2);
  wide.steps[0].overhang_m.add(0.09, 30);
  wide.steps[1].overhang_m.add(0.1, 30);
  EXPECT_EQ(flight_overhang_m(wide, c), c.max_m);
}
