// Plane fits away from concave corners (perception/concave_corners.hpp): a
// time-of-flight sensor's multipath lengthens the paths near the corner where
// a riser meets the tread below it, and the tread's least-squares plane tilts.
#include "perception/concave_corners.hpp"
#include "perception/gravity.hpp"
#include "perception/normals.hpp"
#include "perception/region_growing.hpp"
#include "synthetic.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace stairs {
namespace {

constexpr double kPitch = -35, kHeight = 1.0, kFirstRiser = 1.2, kRiser = 0.17, kTread = 0.28;

// A camera over test::render_stairs' flight: pitch (deg), height over the floor, first riser (m).
struct View {
  double pitch_deg, height_m, first_riser_m;
};
constexpr View kView{kPitch, kHeight, kFirstRiser};

// test::render_stairs seen from `w`, each ray within band_m of a concave corner lengthened by bias_m
// at the corner, falling linearly to 0 (stairs-sim's Kinect v2 model, drivers/sim/sensor.cpp
// apply_multipath): on the tread (or floor) before each riser, and with `on_risers` on the riser
// above the tread too.
DepthImage with_multipath(const View& w, double bias_m, double band_m, bool on_risers) {
  DepthImage img = test::render_stairs(640, 480, w.pitch_deg, 0, w.height_m, 3, w.first_riser_m, kRiser, kTread);
  if (bias_m <= 0) return img;
  const Eigen::Matrix3d R = test::optical_to_world(w.pitch_deg, 0);
  for (int v = 0; v < img.K.height; ++v)
    for (int u = 0; u < img.K.width; ++u) {
      uint16_t& mm = img.depth[static_cast<size_t>(v) * img.K.width + u];
      if (mm == 0) continue;
      const double z = mm / 1000.0;
      const Eigen::Vector3d p = R * Eigen::Vector3d((u - img.K.cx) / img.K.fx * z, (v - img.K.cy) / img.K.fy * z, z);
      const double level = (p.z() + w.height_m) / kRiser;
      double to_corner = band_m;
      for (int k = 0; k < 3; ++k) {  // level k meets the riser at x_k
        const double x_k = w.first_riser_m + k * kTread, z_k = -w.height_m + k * kRiser;
        if (std::abs(level - k) <= 0.02 && p.x() <= x_k) to_corner = std::min(to_corner, x_k - p.x());
        if (on_risers && std::abs(p.x() - x_k) < 0.003 && p.z() >= z_k) to_corner = std::min(to_corner, p.z() - z_k);
      }
      if (to_corner < band_m) mm = static_cast<uint16_t>(std::lround(mm + 1000 * bias_m * (1 - to_corner / band_m)));
    }
  return img;
}

DepthImage stairs_with_multipath(double bias_m, double band_m) { return with_multipath(kView, bias_m, band_m, false); }

Eigen::Vector3f true_up() {
  return (test::optical_to_world(kPitch, 0).transpose() * Eigen::Vector3d::UnitZ()).cast<float>();
}

double deg_from_up(const Eigen::Vector3f& n) {
  return std::acos(std::min(1.0f, std::abs(n.dot(true_up())))) * 180 / M_PI;
}

struct Fitted {
  std::vector<Segment> segments;
  double worst_tread_deg = 0;  // the horizontal segments' largest angle to true up
};

Fitted fit(const DepthImage& img, float band_m) {
  PerceptionConfig cfg;
  cfg.concave_corners.band_m = band_m;
  NormalGrid g;
  compute_normals(img, cfg.normals, g);
  std::vector<int> labels;
  Fitted f;
  f.segments = grow_regions(g, cfg.region_growing, img.K.width, img.K.height, labels);
  ConcaveCornersScratch scratch;
  fit_away_from_concave_corners(g, cfg.concave_corners, f.segments, scratch);
  for (const Segment& s : f.segments)
    if (deg_from_up(s.normal) < 10) f.worst_tread_deg = std::max(f.worst_tread_deg, deg_from_up(s.normal));
  return f;
}

TEST(PerceptionConcaveCorners, TreadsBentByMultipathAreFittedOutsideTheBand) {
  const DepthImage img = stairs_with_multipath(0.015, 0.08);
  const Fitted bent = fit(img, 0.0f);  // the stage off
  const Fitted fixed = fit(img, 0.08f);
  std::printf("worst tread tilt: %.2f deg as fitted, %.2f deg away from the corners\n", bent.worst_tread_deg,
              fixed.worst_tread_deg);
  EXPECT_GT(bent.worst_tread_deg, 0.5);  // the failure this stage is for
  EXPECT_LT(fixed.worst_tread_deg, 0.1);
  // Gravity follows the treads.
  const auto up = estimate_up(fixed.segments, GravityConfig{});
  ASSERT_TRUE(up.has_value());
  EXPECT_LT(deg_from_up(*up), 0.1);
}

TEST(PerceptionConcaveCorners, PlanesWithoutABentBandKeepTheirFit) {
  // Structured light or stereo: no multipath, the band lies on the plane, and
  // every segment keeps the fit of all its cells.
  const DepthImage img = test::render_stairs(640, 480, kPitch, 0, kHeight, 3, kFirstRiser, kRiser, kTread);
  const Fitted off = fit(img, 0.0f), on = fit(img, 0.08f);
  ASSERT_EQ(off.segments.size(), on.segments.size());
  for (size_t i = 0; i < on.segments.size(); ++i) {
    EXPECT_EQ(on.segments[i].normal, off.segments[i].normal) << i;
    EXPECT_EQ(on.segments[i].centroid, off.segments[i].centroid) << i;
    // Treads, floor and risers keep their say in gravity (the small slanted
    // segments of cells straddling the render's edges lie in the bands).
    const double deg = deg_from_up(on.segments[i].normal);
    if (deg < 10 || deg > 80) {
      EXPECT_FALSE(on.segments[i].bent) << i;
    }
  }
}

// A robot looking up a flight, its camera 10 cm above the tread ahead: of that tread it sees the
// last 8 cm before the next riser, edge-on (13 deg), all of it inside the corner's multipath band.
constexpr double kLowHeight = 0.27, kLowPitch = 11.2, kLowFirstRiser = 0.22;

// Seen from it by a time-of-flight camera (`bias_m` > 0): multipath on both faces of each corner.
DepthImage low_view(double bias_m, double band_m) {
  return with_multipath({kLowPitch, kLowHeight, kLowFirstRiser}, bias_m, band_m, true);
}

Eigen::Vector3f low_up() {
  return (test::optical_to_world(kLowPitch, 0).transpose() * Eigen::Vector3d::UnitZ()).cast<float>();
}

std::vector<Segment> low_segments(const DepthImage& img) {
  PerceptionConfig cfg;
  NormalGrid g;
  compute_normals(img, cfg.normals, g);
  std::vector<int> labels;
  std::vector<Segment> segments = grow_regions(g, cfg.region_growing, img.K.width, img.K.height, labels);
  ConcaveCornersScratch scratch;
  fit_away_from_concave_corners(g, cfg.concave_corners, segments, scratch);
  return segments;
}

// The tread strip lies wholly in the band, so its own cells cannot show the bend (no core to fit);
// the riser it meets shows the multipath, and the strip's tilt (2 deg: the bias along a ray 13 deg
// off the tread) must not set up.
TEST(PerceptionConcaveCorners, ATreadStripInsideABentCornersBandDoesNotStandForUp) {
  const std::vector<Segment> segments = low_segments(low_view(0.015, 0.08));
  double strip_deg = 0;
  for (const Segment& s : segments) {
    const double deg = std::acos(std::min(1.0f, std::abs(s.normal.dot(low_up())))) * 180 / M_PI;
    if (deg > 10) continue;
    std::printf("tread strip: %zu cells, %.2f deg from up, bent %d\n", s.cells.size(), deg, s.bent);
    strip_deg = std::max(strip_deg, deg);
  }
  ASSERT_GT(strip_deg, 1.0);  // the failure: multipath tilts the strip
  // With the previous frame's up (looking up a flight the risers would otherwise stand for it).
  const auto up = estimate_up(segments, GravityConfig{}, low_up());
  ASSERT_TRUE(up.has_value());
  const double off = std::acos(std::min(1.0f, up->dot(low_up()))) * 180 / M_PI;
  std::printf("up %.2f deg off\n", off);
  // Not the strip's up; the risers, bent at their feet too, leave a fraction of a degree.
  EXPECT_LT(off, 0.5 * strip_deg);
}

// Structured light or stereo at the same view: the corner shows no bend, and the strip keeps its say.
TEST(PerceptionConcaveCorners, ATreadStripInsideAStraightCornersBandKeepsItsFit) {
  const std::vector<Segment> segments = low_segments(low_view(0.0, 0.08));
  int strips = 0;
  for (const Segment& s : segments)
    if (std::abs(s.normal.dot(low_up())) > std::cos(10 * M_PI / 180)) {
      ++strips;
      EXPECT_FALSE(s.bent);
    }
  EXPECT_GE(strips, 1);
  const auto up = estimate_up(segments, GravityConfig{}, low_up());
  ASSERT_TRUE(up.has_value());
  std::printf("up %.2f deg off\n", std::acos(std::min(1.0f, up->dot(low_up()))) * 180 / M_PI);
  EXPECT_LT(std::acos(std::min(1.0f, up->dot(low_up()))) * 180 / M_PI, 0.3);
}

}  // namespace
}  // namespace stairs
