#include "perception/gravity.hpp"
#include "perception/normals.hpp"
#include "perception/region_growing.hpp"
#include "synthetic.hpp"

#include <Eigen/Geometry>

#include <random>

#include <gtest/gtest.h>

namespace stairs {
namespace {

TEST(PerceptionNormals, FloorNormalsPointUpTowardsTheCamera) {
  const DepthImage img = test::render_stairs(320, 240, -40, 5, 1.0, 0);
  NormalGrid g;
  compute_normals(img, NormalsConfig{}, g);
  EXPECT_EQ(g.width, 160);
  EXPECT_EQ(g.height, 120);
  // Floor normal (world up) in optical coordinates.
  const Eigen::Vector3f up = (test::optical_to_world(-40, 5).transpose() * Eigen::Vector3d::UnitZ()).cast<float>();
  int n = 0, close = 0;
  for (size_t i = 0; i < g.normals.size(); ++i) {
    if (!g.has_normal[i]) continue;
    ++n;
    if (g.normals[i].dot(up) > std::cos(2.0 * M_PI / 180)) ++close;
  }
  EXPECT_GT(n, 10000);
  EXPECT_GT(close, 0.98 * n);
}

TEST(PerceptionNormals, EmptyAndTinyFramesGiveNoNormals) {
  PerceptionConfig cfg;
  NormalGrid g;
  DepthImage img;
  img.K = {3, 2, 1, 1, 1, 1};
  img.depth.assign(6, 1000);
  compute_normals(img, cfg.normals, g);
  for (uint8_t h : g.has_normal) EXPECT_EQ(h, 0);
}

// Cells with a point (and with a normal) over the whole grid.
std::pair<int, int> grid_counts(const NormalGrid& g) {
  int points = 0, normals = 0;
  for (size_t i = 0; i < g.has_point.size(); ++i) points += g.has_point[i], normals += g.has_normal[i];
  return {points, normals};
}

// A surface that absorbs the IR (dark treads) returns nothing on half its
// pixels at random: its cells are still that surface, with half their pixels
// measured. Counted against the cell's area, about half the cells had no point
// and region growing found no tread (a D435 robot descent: 3 of 10 steps).
TEST(PerceptionNormals, ASurfaceThatReturnsHalfItsPixelsKeepsItsCells) {
  const DepthImage full = test::render_stairs(640, 480, -40, 0, 1.0, 0);  // a floor 1.3-2.8 m away
  DepthImage dark = full;
  std::mt19937 rng(7);
  std::bernoulli_distribution drop(0.5);
  for (uint16_t& d : dark.depth)
    if (drop(rng)) d = 0;
  NormalGrid a, b;
  compute_normals(full, NormalsConfig{}, a);
  compute_normals(dark, NormalsConfig{}, b);
  const auto [full_points, full_normals] = grid_counts(a);
  const auto [dark_points, dark_normals] = grid_counts(b);
  EXPECT_GT(full_points, 15000);
  EXPECT_GT(dark_points, 0.97 * full_points);
  EXPECT_GT(dark_normals, 0.95 * full_normals);
  // The points stay on the floor: 1 m below the camera within a centimetre.
  const Eigen::Matrix3d R = test::optical_to_world(-40, 0);
  int off = 0;
  for (size_t i = 0; i < b.points.size(); ++i)
    if (b.has_point[i] && std::abs((R * b.points[i].cast<double>()).z() + 1.0) > 0.01) ++off;
  EXPECT_LT(off, 0.01 * dark_points);
}

// A few returns make no mean, and a cell's nearest surface must still hold half
// of what it measured: flying pixels in front of a surface are no point,
// whether the surface behind them returned all its pixels or half.
TEST(PerceptionNormals, FewReturnsAndFlyingPixelsMakeNoPoint) {
  DepthImage img;
  img.K = {64, 64, 52.5, 52.5, 31.5, 31.5};
  img.depth.assign(64 * 64, 1000);  // a wall 1 m away, 4x4 px cells
  NormalsConfig cfg;
  cfg.grid_cell_px = 40;  // 4 px at 64 wide
  const auto cell = [&](int gx, int gy, int k) -> uint16_t& { return img.depth[(gy * 4 + k / 4) * 64 + gx * 4 + k % 4]; };
  // Cell (2, 2): 3 of 16 pixels measured.
  for (int k = 3; k < 16; ++k) cell(2, 2, k) = 0;
  // Cell (5, 5): 2 flying pixels 20 cm in front of the wall, all the rest measured.
  cell(5, 5, 0) = cell(5, 5, 2) = 800;
  // Cell (8, 8): the same 2 flying pixels, and half the wall's pixels dropped.
  cell(8, 8, 0) = cell(8, 8, 2) = 800;
  for (int k = 1; k < 16; k += 2) cell(8, 8, k) = 0;
  // Cell (11, 11): 6 of 16 pixels measured, all on the wall: a point.
  for (int k = 0; k < 10; ++k) cell(11, 11, k) = 0;
  NormalGrid g;
  compute_normals(img, cfg, g);
  ASSERT_EQ(g.width, 16);
  EXPECT_FALSE(g.has_point[g.index(2, 2)]);
  EXPECT_FALSE(g.has_point[g.index(5, 5)]);
  EXPECT_FALSE(g.has_point[g.index(8, 8)]);
  EXPECT_TRUE(g.has_point[g.index(11, 11)]);
  EXPECT_NEAR(g.points[g.index(11, 11)].z(), 1.0f, 1e-4f);
  EXPECT_TRUE(g.has_point[g.index(1, 1)]);
}

TEST(PerceptionRegionGrowing, StairsAreSegmentedIntoTreadsAndRisers) {
  const DepthImage img = test::render_stairs(640, 480, -35, 0, 1.0, 3, 1.2);
  PerceptionConfig cfg;
  NormalGrid g;
  compute_normals(img, cfg.normals, g);
  std::vector<int> labels;
  const auto segs = grow_regions(g, cfg.region_growing, 640, 480, labels);
  // Floor, 3 treads, 3 risers; over-segmentation is allowed, mixing is not.
  ASSERT_GE(segs.size(), 7u);
  for (const Segment& s : segs) EXPECT_LT(s.rms_m, 0.01f);
  // The top level is in view: floor + 3 treads + 3 risers at least.
}

// A tread seen from above between two depth jumps, as a time-of-flight camera reads it: its far row
// of cells mixed with the level beyond (3 % farther along the ray), its near row with the nosing in
// front (3 % nearer). Its plane is fitted to the rows between; all of them tilt it.
TEST(PerceptionRegionGrowing, AStripBetweenDepthJumpsIsFittedAwayFromItsMixedEdges) {
  const int w = 80, h = 60, cell = 8;
  const Intrinsics K{640, 480, 525.0, 525.0, 319.5, 239.5};
  NormalGrid g;
  g.width = w, g.height = h, g.cell_px = cell;
  g.points.assign(w * h, Eigen::Vector3f::Zero());
  g.normals.assign(w * h, Eigen::Vector3f::Zero());
  g.has_point.assign(w * h, 0);
  g.has_normal.assign(w * h, 0);
  g.filled.assign(w * h, 0);
  const float below_m = 0.5f;  // the tread's plane y = below_m (optical frame, y down)
  // Rows 40-47 are the tread; row 39 the level beyond (30 % farther), row 48 the nosing (30 % nearer).
  const auto scale_of_row = [](int gy) { return gy == 39 ? 1.3f : gy == 40 ? 1.03f : gy == 47 ? 0.97f : gy == 48 ? 0.7f : 1.0f; };
  for (int gy = 39; gy <= 48; ++gy)
    for (int gx = 0; gx < w; ++gx) {
      const Eigen::Vector3f ray(static_cast<float>(((gx + 0.5) * cell - K.cx) / K.fx),
                                static_cast<float>(((gy + 0.5) * cell - K.cy) / K.fy), 1.0f);
      const int i = g.index(gx, gy);
      g.points[i] = ray * (below_m / ray.y()) * scale_of_row(gy);
      g.normals[i] = -Eigen::Vector3f::UnitY();
      g.has_point[i] = g.has_normal[i] = g.filled[i] = 1;
    }
  const auto tread_tilt_deg = [&](const RegionGrowingConfig& cfg) {
    std::vector<int> labels;
    const auto segs = grow_regions(g, cfg, K.width, K.height, labels);
    for (const Segment& s : segs)
      if (s.cells.size() == static_cast<size_t>(8 * w))
        return std::acos(std::min(1.0f, s.normal.dot(-Eigen::Vector3f::UnitY()))) * 180.0 / M_PI;
    ADD_FAILURE() << "no segment of the tread's 8 rows among " << segs.size();
    return 180.0;
  };
  RegionGrowingConfig cfg;
  EXPECT_LT(tread_tilt_deg(cfg), 0.05);
  cfg.fit_jump_ratio = 0.0f;  // all its cells: the mixed rows tilt it
  EXPECT_GT(tread_tilt_deg(cfg), 0.5);
}

TEST(PerceptionRegionGrowing, SmallPlanesAreDroppedWithTheScaledThreshold) {
  PerceptionConfig cfg;
  cfg.region_growing.min_plane_px_320 = 1000000;  // larger than any frame
  const DepthImage img = test::render_stairs(320, 240, -35, 0, 1.0, 0);
  NormalGrid g;
  compute_normals(img, cfg.normals, g);
  std::vector<int> labels;
  EXPECT_TRUE(grow_regions(g, cfg.region_growing, 320, 240, labels).empty());
  for (int l : labels) EXPECT_EQ(l, -1);
}

TEST(PerceptionGravity, PoseConventionsRoundTrip) {
  for (double pitch : {-75.0, -35.0, -5.0, 10.0})
    for (double roll : {-10.0, 0.0, 4.0}) {
      const Eigen::Matrix3d R = test::optical_to_world(pitch, roll);
      const Eigen::Vector3f up = (R.transpose() * Eigen::Vector3d::UnitZ()).cast<float>();
      const CameraPose p = pose_from_up(up);
      EXPECT_NEAR(p.pitch_deg, pitch, 1e-3);
      EXPECT_NEAR(p.roll_deg, roll, 1e-3);
      // gravity_rotation maps optical into x forward, y left, z up: the
      // same as the world frame up to yaw (zero here).
      const Eigen::Matrix3d G = p.gravity_rotation.toRotationMatrix();
      EXPECT_TRUE(G.isApprox(R, 1e-5)) << "pitch " << pitch << " roll " << roll;
    }
}

TEST(PerceptionGravity, PitchAndRollFromTheFloorAndSteps) {
  const DepthImage img = test::render_stairs(640, 480, -30, 3, 1.1, 3, 1.5);
  PerceptionConfig cfg;
  NormalGrid g;
  compute_normals(img, cfg.normals, g);
  std::vector<int> labels;
  const auto segs = grow_regions(g, cfg.region_growing, 640, 480, labels);
  const auto up = estimate_up(segs, cfg.gravity);
  ASSERT_TRUE(up.has_value());
  const CameraPose p = pose_from_up(*up);
  EXPECT_NEAR(p.pitch_deg, -30, 0.3);
  EXPECT_NEAR(p.roll_deg, 3, 0.3);
}

TEST(PerceptionGravity, NoHorizontalPlaneNoPose) {
  // A wall straight ahead: its normal is 90 deg from image up.
  Segment wall;
  wall.normal = {0, 0, -1};
  wall.cells.assign(5000, 0);
  EXPECT_FALSE(estimate_up({wall}, GravityConfig{}).has_value());
}

}  // namespace
// Segments of a stair seen by a camera at `pitch_deg`: `tread_cells` of
// horizontal planes, risers facing the camera and a side wall.
// The fit of a plane the size of a step: 2 mm rms over 0.6 x 0.2 m (the
// spread is the variance along each in-plane axis).
void plane_fit_of_a_step(Segment& s) {
  s.rms_m = 0.002f;
  const Eigen::Vector3f a0 = s.normal.unitOrthogonal();
  s.axis[0] = a0, s.axis[1] = s.normal.cross(a0).normalized();
  s.spread_m2[0] = 0.6f * 0.6f / 12.0f;
  s.spread_m2[1] = 0.2f * 0.2f / 12.0f;
}

std::vector<Segment> stair_segments(double pitch_deg, size_t tread_cells, size_t riser_cells, size_t wall_cells) {
  const Eigen::Matrix3d Rt = test::optical_to_world(pitch_deg, 0).transpose();
  auto segment = [&](const Eigen::Vector3d& world_normal, size_t cells) {
    Segment s;
    s.normal = (Rt * world_normal).cast<float>();
    s.cells.assign(cells, 0);
    plane_fit_of_a_step(s);
    return s;
  };
  std::vector<Segment> segs;
  if (tread_cells) segs.push_back(segment(Eigen::Vector3d::UnitZ(), tread_cells));
  if (riser_cells) segs.push_back(segment(-Eigen::Vector3d::UnitX(), riser_cells));
  if (wall_cells) segs.push_back(segment(-Eigen::Vector3d::UnitY(), wall_cells));
  return segs;
}

// A segment as a plane fit leaves it: normal (given in the world, seen from a
// camera at pitch_deg), cells, the standard deviations of its cells along its
// two in-plane axes, and the fit's rms.
Segment fitted_segment(double pitch_deg, const Eigen::Vector3d& world_normal, size_t cells, double spread0_m,
                       double spread1_m, float rms_m) {
  Segment s;
  s.normal = (test::optical_to_world(pitch_deg, 0).transpose() * world_normal).cast<float>();
  s.cells.assign(cells, 0);
  const Eigen::Vector3f a0 = s.normal.unitOrthogonal();
  s.axis[0] = a0, s.axis[1] = s.normal.cross(a0).normalized();
  s.spread_m2[0] = static_cast<float>(spread0_m * spread0_m);
  s.spread_m2[1] = static_cast<float>(spread1_m * spread1_m);
  s.rms_m = rms_m;
  return s;
}

// The same, its centroid depth_m ahead of the camera (the depth its fit's noise floor grows with).
Segment fitted_segment_at(double pitch_deg, const Eigen::Vector3d& world_normal, size_t cells, double spread0_m,
                          double spread1_m, float rms_m, float depth_m) {
  Segment s = fitted_segment(pitch_deg, world_normal, cells, spread0_m, spread1_m, rms_m);
  s.centroid = Eigen::Vector3f(0, 0, depth_m);
  return s;
}

// A level plane seen from a camera at pitch_deg, its fit tilted tilt_deg in pitch, its spread along_m
// (standard deviation) along the levelled view and across_m across it: how well it knows its tilt along
// the view is what a flight's pitch depends on.
Segment tread_along_view(double pitch_deg, double tilt_deg, size_t cells, double along_m, double across_m, float rms_m,
                         float depth_m) {
  const Eigen::Vector3d tilted = Eigen::AngleAxisd(tilt_deg * M_PI / 180, Eigen::Vector3d::UnitY()) * Eigen::Vector3d::UnitZ();
  Segment s = fitted_segment_at(pitch_deg, tilted, cells, along_m, across_m, rms_m, depth_m);
  const Eigen::Vector3f forward = (test::optical_to_world(pitch_deg, 0).transpose() * Eigen::Vector3d::UnitX()).cast<float>();
  s.axis[0] = (forward - forward.dot(s.normal) * s.normal).normalized();
  s.axis[1] = s.normal.cross(s.axis[0]).normalized();
  return s;
}

Eigen::Vector3f true_up(double pitch_deg) {
  return (test::optical_to_world(pitch_deg, 0).transpose() * Eigen::Vector3d::UnitZ()).cast<float>();
}

TEST(PerceptionGravity, PriorTellsTreadsFromDominantRisers) {
  // A robot looking up a flight at +15 deg: the risers are 75 deg from image
  // up and dominate; alone, the frame is ambiguous and the risers win.
  const auto segs = stair_segments(15, 2000, 10000, 0);
  const auto alone = estimate_up(segs, GravityConfig{});
  ASSERT_TRUE(alone.has_value());
  EXPECT_LT(alone->dot(true_up(15)), 0.5f);
  const auto tracked = estimate_up(segs, GravityConfig{}, true_up(10));
  ASSERT_TRUE(tracked.has_value());
  EXPECT_GT(tracked->dot(true_up(15)), std::cos(0.1 * M_PI / 180));
}

// A robot tipping over a nosing looks 88 deg down for a frame: the treads face the camera, more than
// max_tilt_from_image_up_deg (80) from image up. Without a prior nothing tells them from a wall
// ahead; with the previous frame's up (76 deg down) they are up, not the prior kept (a Kinect v1
// robot's descent: that frame's rises 13 cm for 18, three false steps).
TEST(PerceptionGravity, APriorLetsACameraLookingStraightDownFindTheTreads) {
  const auto segs = stair_segments(-88, 10000, 0, 0);
  EXPECT_FALSE(estimate_up(segs, GravityConfig{}).has_value());
  const auto up = estimate_up(segs, GravityConfig{}, true_up(-76));
  ASSERT_TRUE(up.has_value());
  EXPECT_GT(up->dot(true_up(-88)), std::cos(0.1 * M_PI / 180));
}

TEST(PerceptionGravity, VerticalPlanesFixUpWhenTreadsAreMissing) {
  const auto segs = stair_segments(15, 0, 10000, 3000);
  const auto up = estimate_up(segs, GravityConfig{}, true_up(9));
  ASSERT_TRUE(up.has_value());
  EXPECT_GT(up->dot(true_up(15)), std::cos(0.1 * M_PI / 180));
  // Risers alone keep the prior's roll and take their pitch.
  const auto risers_only = estimate_up(stair_segments(15, 0, 10000, 0), GravityConfig{}, true_up(9));
  ASSERT_TRUE(risers_only.has_value());
  EXPECT_GT(risers_only->dot(true_up(15)), std::cos(0.1 * M_PI / 180));
  // A plane neither near the prior nor near vertical under it gives nothing.
  EXPECT_FALSE(estimate_up(stair_segments(15, 0, 10000, 0), GravityConfig{}, true_up(-35)).has_value());
}

TEST(PerceptionGravity, TinyTreadsYieldToTheVerticalPlanes) {
  // 100 cells of noise near the prior against 10000 of risers and walls.
  auto segs = stair_segments(15, 0, 10000, 3000);
  Segment noise;
  noise.normal = true_up(2);  // 13 deg off: a badly determined small patch
  noise.cells.assign(100, 0);
  segs.push_back(noise);
  const auto up = estimate_up(segs, GravityConfig{}, true_up(9));
  ASSERT_TRUE(up.has_value());
  EXPECT_GT(up->dot(true_up(15)), std::cos(0.1 * M_PI / 180));
}

// A level camera 0.9 m high before a flight (the level_09m walks): walls and
// risers dominate the support, and the risers, 3 m away and noisy, lean 1.5
// deg, so up from walls x risers is 1.5 deg off. The floor and a tread, too
// small to choose up beside the walls, still fix it where they agree: up is
// fitted to them, each by how well its own fit knows its normal.
TEST(PerceptionGravity, TreadsTooSmallToChooseStillFitUp) {
  const double pitch = -2.4;
  const Eigen::Matrix3d Rt = test::optical_to_world(pitch, 0).transpose();
  auto segment = [&](const Eigen::Vector3d& world_normal, size_t cells, const Eigen::Vector3d& a0, double spread0,
                     const Eigen::Vector3d& a1, double spread1, float rms_m) {
    Segment s;
    s.normal = (Rt * world_normal).cast<float>();
    s.cells.assign(cells, 0);
    s.axis[0] = (Rt * a0).cast<float>(), s.axis[1] = (Rt * a1).cast<float>();
    s.spread_m2[0] = static_cast<float>(spread0), s.spread_m2[1] = static_cast<float>(spread1);
    s.rms_m = rms_m;
    return s;
  };
  const Eigen::Vector3d X = Eigen::Vector3d::UnitX(), Y = Eigen::Vector3d::UnitY(), Z = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d leaning = Eigen::AngleAxisd(1.5 * M_PI / 180, Y) * -X;
  std::vector<Segment> segs = {
      segment(-Y, 6000, X, 1.0, Z, 0.3, 0.0009f),  // the walls
      segment(leaning, 2500, Y, 0.08, Z, 0.003, 0.006f),  // far risers
      segment(Z, 360, Y, 0.08, X, 0.004, 0.0015f),  // the floor before the flight: a strip
      segment(Z, 220, Y, 0.08, X, 0.005, 0.0014f),  // the first tread
  };
  const auto up = estimate_up(segs, GravityConfig{}, true_up(pitch - 1.0));
  ASSERT_TRUE(up.has_value());
  EXPECT_GT(up->dot(true_up(pitch)), std::cos(0.1 * M_PI / 180));
  // Without the treads, walls x risers (the branch this refines).
  segs.resize(2);
  const auto walls_risers = estimate_up(segs, GravityConfig{}, true_up(pitch - 1.0));
  ASSERT_TRUE(walls_risers.has_value());
  EXPECT_LT(walls_risers->dot(true_up(pitch)), std::cos(1.0 * M_PI / 180));
}

// A robot on a flight looking up it (+10 deg, the randomised robot ascents): a
// side wall, risers whose fits lean 5 deg (cells at the nosings mix the next
// riser's depth in: rms 3.5 mm over their 4 cm height) and one tread beside
// the camera, flat and wide but with fewer cells than the wall has. Walls x
// risers put up 5 deg off; the tread's fit knows its normal far better than
// the risers know theirs, so up is the one it agrees with.
TEST(PerceptionGravity, AWellFittedTreadOutvotesRisersBentAtTheirNosings) {
  const double pitch = 10.0;
  auto segment = [&](const Eigen::Vector3d& world_normal, size_t cells, double spread0_m, double spread1_m,
                     float rms_m) { return fitted_segment(pitch, world_normal, cells, spread0_m, spread1_m, rms_m); };
  const Eigen::Vector3d X = Eigen::Vector3d::UnitX(), Y = Eigen::Vector3d::UnitY(), Z = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d leaning = Eigen::AngleAxisd(5.0 * M_PI / 180, Y) * -X;
  std::vector<Segment> segs = {segment(-Y, 6400, 0.6, 0.9, 0.0011f), segment(Y, 2200, 0.2, 0.7, 0.0010f)};
  for (size_t cells : {1400, 2300, 1300, 640}) segs.push_back(segment(leaning, cells, 0.04, 0.22, 0.0035f));
  segs.push_back(segment(Z, 600, 0.19, 0.42, 0.0012f));
  const auto up = estimate_up(segs, GravityConfig{}, true_up(pitch - 4.0));
  ASSERT_TRUE(up.has_value());
  EXPECT_GT(up->dot(true_up(pitch)), std::cos(0.1 * M_PI / 180));
}

TEST(PerceptionGravity, FarSliversBesideParallelWallsDoNotSetPitch) {
  // A level camera at the top of a flight going down, between two walls: the
  // walls fix up only across them, the previous frame's up the rest, and the
  // only level planes are treads 4.4 m away seen as slivers (a few cm deep),
  // their fits 2.5 deg off in pitch (depth noise at that range). Up stays with
  // the prior: the slivers know their normals to worse than consensus_deg.
  const double pitch = -7.0;
  auto segment = [&](const Eigen::Vector3d& world_normal, size_t cells, double spread0_m, double spread1_m,
                     float rms_m, float depth_m) {
    return fitted_segment_at(pitch, world_normal, cells, spread0_m, spread1_m, rms_m, depth_m);
  };
  const Eigen::Vector3d Y = Eigen::Vector3d::UnitY(), Z = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d tilted = Eigen::AngleAxisd(2.5 * M_PI / 180, Y) * Z;  // pitch, about the walls' normal
  const std::vector<Segment> segs = {segment(Y, 5700, 0.58, 0.86, 0.003f, 3.3f),
                                     segment(-Y, 2200, 0.43, 0.49, 0.001f, 1.9f),
                                     segment(tilted, 151, 0.063, 0.35, 0.0056f, 4.4f),
                                     segment(tilted, 38, 0.06, 0.11, 0.005f, 4.4f)};
  bool carried = false;
  const auto up = estimate_up(segs, GravityConfig{}, true_up(pitch), &carried);
  ASSERT_TRUE(up.has_value());
  EXPECT_GT(up->dot(true_up(pitch)), std::cos(0.5 * M_PI / 180));
  EXPECT_TRUE(carried);  // the pitch is the prior's: the pipeline keeps it gravity.carry_max_s at most
  // A tread near the camera that knows its normal measures the pitch itself.
  std::vector<Segment> with_tread = segs;
  with_tread.push_back(segment(Z, 900, 0.12, 0.5, 0.0012f, 1.2f));
  const auto measured = estimate_up(with_tread, GravityConfig{}, true_up(pitch - 1.0), &carried);
  ASSERT_TRUE(measured.has_value());
  EXPECT_GT(measured->dot(true_up(pitch)), std::cos(0.1 * M_PI / 180));
  EXPECT_FALSE(carried);
}

// The same landing a step further on (a hand-held Kinect v1 level descent): the far tread grew to
// 227 cells 30 cm deep at 4.3 m, whose noise alone (6 mm over 227 cells) knows its tilt to 1.2
// degrees; it was 2.2 off, the frame counted its pitch as measured, and the flight's real steps
// below came out unmatched (9 false frames, 3 false model steps). The depth's resolution at 4.3 m
// (quantised disparity: a few terraces across the tread) does not average over cells: the tilt is
// known to resolution / depth at best, so the pitch counts as carried (the pipeline keeps it
// gravity.carry_max_s at most, then the pose is unknown).
TEST(PerceptionGravity, AFarTreadMeasuresPitchOnlyToTheDepthResolutionAcrossIt) {
  const double pitch = -7.7;
  // The tread: 9 cm (standard deviation) along the view, 38 cm across it; the side walls.
  const Segment tread = tread_along_view(pitch, 2.2, 227, 0.089, 0.377, 0.0063f, 4.34f);
  const std::vector<Segment> segs = {fitted_segment_at(pitch, Eigen::Vector3d::UnitY(), 5811, 0.59, 0.85, 0.0031f, 3.3f),
                                     fitted_segment_at(pitch, -Eigen::Vector3d::UnitY(), 2370, 0.53, 0.57, 0.0011f, 2.1f),
                                     tread};
  bool carried = false;
  ASSERT_TRUE(estimate_up(segs, GravityConfig{}, true_up(pitch), &carried).has_value());
  EXPECT_TRUE(carried);
}

// A level camera reaching the top of a descent between two walls (a Kinect v2 level walk): the only
// level plane is the landing's edge, a strip 1.4 cm deep (standard deviation) at 1.4 m whose fit is
// 3 deg off in pitch. Its fit knows its normal well enough to win the walls' consensus, but not to
// the depth's resolution across it: the pitch is carried, and a carried pitch is the prior's. It was
// the strip's, and the flight's first three frames measured every rise 1.5 cm short.
TEST(PerceptionGravity, ACarriedPitchIsThePriorsNotTheStripsThatCouldNotMeasureIt) {
  const double pitch = -10.0;
  const Segment strip = tread_along_view(pitch, 3.0, 285, 0.014, 0.38, 0.0015f, 1.41f);
  const std::vector<Segment> segs = {fitted_segment_at(pitch, Eigen::Vector3d::UnitY(), 7427, 0.79, 0.83, 0.0011f, 2.5f),
                                     fitted_segment_at(pitch, -Eigen::Vector3d::UnitY(), 4207, 0.49, 1.12, 0.0010f, 3.5f),
                                     strip};
  bool carried = false;
  const auto up = estimate_up(segs, GravityConfig{}, true_up(pitch), &carried);
  ASSERT_TRUE(up.has_value());
  EXPECT_TRUE(carried);
  EXPECT_GT(up->dot(true_up(pitch)), std::cos(0.1 * M_PI / 180));
  // The prior's pitch weighs by how well it is still known: one known to a degree (a tenth of a
  // second's sway) keeps most of it, one hardly known gives way to what the strip says.
  const auto one_degree = estimate_up(segs, GravityConfig{}, true_up(pitch), &carried, std::pow(180 / M_PI, 2));
  ASSERT_TRUE(one_degree.has_value());
  EXPECT_GT(one_degree->dot(true_up(pitch)), std::cos(0.5 * M_PI / 180));
  const auto unknown = estimate_up(segs, GravityConfig{}, true_up(pitch), &carried, 1e-6);
  ASSERT_TRUE(unknown.has_value());
  EXPECT_GT(unknown->dot(strip.normal), std::cos(0.1 * M_PI / 180));
}

// A hand-held Kinect v1 at the top of a descent between two walls, the flight beyond the depth's
// range: besides the walls, a 38-cell patch 4.5 m off facing the camera (1 cm rms over 5-8 cm), its
// fit 11 deg off vertical. It was a second vertical family, and up the cross product of its normal
// and the walls': the pitch 12 deg off, and the near landing made six steps. A plane that does not
// know its normal to within consensus_deg stands for no family; a riser that does still fixes up.
TEST(PerceptionGravity, APatchThatDoesNotKnowItsNormalIsNoVerticalFamily) {
  const double pitch = -25.0;
  const Eigen::Vector3d X = Eigen::Vector3d::UnitX(), Y = Eigen::Vector3d::UnitY();
  const Eigen::Vector3d tilted_face = Eigen::AngleAxisd(11.0 * M_PI / 180, Y) * -X;
  std::vector<Segment> segs = {fitted_segment_at(pitch, Y, 9300, 0.51, 0.87, 0.0012f, 1.9f),
                               fitted_segment_at(pitch, -Y, 4000, 0.53, 0.77, 0.0013f, 2.0f),
                               fitted_segment_at(pitch, tilted_face, 38, 0.047, 0.077, 0.0103f, 4.45f)};
  bool carried = false;
  const auto up = estimate_up(segs, GravityConfig{}, true_up(pitch), &carried);
  ASSERT_TRUE(up.has_value());
  EXPECT_GT(up->dot(true_up(pitch)), std::cos(0.5 * M_PI / 180));
  EXPECT_TRUE(carried);  // only the walls fix up: the pitch is the prior's, gravity.carry_max_s at most
  // A riser 2 m off that knows its normal (600 cells, 2 mm rms over 5 x 30 cm) is a second family:
  // it and the walls fix up, the prior 3 deg off.
  segs.push_back(fitted_segment_at(pitch, -X, 600, 0.05, 0.3, 0.002f, 2.0f));
  const auto fixed = estimate_up(segs, GravityConfig{}, true_up(pitch - 3.0), &carried);
  ASSERT_TRUE(fixed.has_value());
  EXPECT_GT(fixed->dot(true_up(pitch)), std::cos(0.2 * M_PI / 180));
  EXPECT_FALSE(carried);
}

TEST(PerceptionGravity, ABentTreadIsOutvotedByThePlanesThatAgree) {
  // A camera at -2.4 deg (level, 0.9 m high) in front of a flight: two treads
  // of the same size, one of them tilted 3.3 deg as a whole (all of it in a
  // time-of-flight sensor's multipath band), and the risers. Averaged, the two
  // treads put up 1.6 deg off; the risers agree with the straight one.
  auto segs = stair_segments(-2.4, 650, 3000, 0);
  Segment bent;
  bent.normal = true_up(-2.4 + 3.3);
  bent.cells.assign(630, 0);
  plane_fit_of_a_step(bent);
  segs.push_back(bent);
  for (const auto& prior : {std::optional<Eigen::Vector3f>{}, std::optional(true_up(-2.0))}) {
    const auto up = estimate_up(segs, GravityConfig{}, prior);
    ASSERT_TRUE(up.has_value());
    EXPECT_GT(up->dot(true_up(-2.4)), std::cos(0.1 * M_PI / 180));
  }
  // With nothing else to agree with, the two treads are averaged (as before).
  GravityConfig wide;
  wide.consensus_deg = 5.0f;
  const auto averaged = estimate_up(segs, wide);
  ASSERT_TRUE(averaged.has_value());
  EXPECT_LT(averaged->dot(true_up(-2.4)), std::cos(1.0 * M_PI / 180));
}

// A robot at -20 deg before a flight of dark treads, on a time-of-flight camera: the treads return
// too little to segment, the risers and the side walls are large, and the floor's strip between the
// camera's minimum range and the first riser lies wholly in the multipath band of that corner, bent
// 7.7 deg as a whole and fitted well (it is flat, only tilted). It is the one tread family and large
// enough beside the risers to propose, but every riser and wall disagrees with it: up is theirs.
TEST(PerceptionGravity, AStripEveryRiserAndWallDisagreesWithDoesNotSetUp) {
  const double pitch = -20.0;
  auto segment = [&](const Eigen::Vector3d& world_normal, size_t cells, double spread0_m, double spread1_m,
                     float rms_m) { return fitted_segment(pitch, world_normal, cells, spread0_m, spread1_m, rms_m); };
  const Eigen::Vector3d X = Eigen::Vector3d::UnitX(), Y = Eigen::Vector3d::UnitY(), Z = Eigen::Vector3d::UnitZ();
  std::vector<Segment> segs = {segment(-Y, 270, 0.05, 0.1, 0.002f), segment(Y, 180, 0.05, 0.1, 0.0015f)};
  for (size_t cells : {1480, 3930, 4800, 5440}) segs.push_back(segment(-X, cells, 0.05, 0.29, 0.002f));
  const Eigen::Vector3d bent = Eigen::AngleAxisd(7.7 * M_PI / 180, Y) * Z;
  segs.push_back(segment(bent, 1680, 0.03, 0.29, 0.0006f));
  const auto up = estimate_up(segs, GravityConfig{}, true_up(pitch - 1.0));
  ASSERT_TRUE(up.has_value());
  EXPECT_GT(up->dot(true_up(pitch)), std::cos(0.1 * M_PI / 180));
  // A strip the risers and walls agree with still sets it (the treads' path, as before).
  segs.back() = segment(Z, 1680, 0.03, 0.29, 0.0006f);
  const auto level = estimate_up(segs, GravityConfig{}, true_up(pitch - 1.0));
  ASSERT_TRUE(level.has_value());
  EXPECT_GT(level->dot(true_up(pitch)), std::cos(0.1 * M_PI / 180));
}

}  // namespace stairs

namespace stairs {
namespace {

// A face seen from a camera at pitch_deg: its world normal, its cells' standard deviations up its
// height (vertical_m) and along its width (horizontal_m), its fit's rms and depth.
Segment face_at(double pitch_deg, const Eigen::Vector3d& world_normal, size_t cells, double vertical_m,
                double horizontal_m, float rms_m, float depth_m) {
  Segment s = fitted_segment_at(pitch_deg, world_normal, cells, vertical_m, horizontal_m, rms_m, depth_m);
  const Eigen::Vector3f up = true_up(pitch_deg);
  s.axis[0] = (up - up.dot(s.normal) * s.normal).normalized();
  s.axis[1] = s.normal.cross(s.axis[0]).normalized();
  return s;
}

// Four risers facing the camera, riser i leaning lean_deg[i] back from plumb, its fit as face_at's.
std::vector<Segment> leaning_risers(double pitch_deg, const double (&lean_deg)[4], const size_t (&cells)[4],
                                    double vertical_m, double horizontal_m, const float (&rms_m)[4],
                                    const float (&depth_m)[4]) {
  std::vector<Segment> risers;
  for (int i = 0; i < 4; ++i)
    risers.push_back(face_at(pitch_deg,
                             Eigen::AngleAxisd(-lean_deg[i] * M_PI / 180, Eigen::Vector3d::UnitY()) * -Eigen::Vector3d::UnitX(),
                             cells[i], vertical_m, horizontal_m, rms_m[i], depth_m[i]));
  return risers;
}

// A level Kinect v2 1.4 m up, 2.8 m before a flight between two walls (seed 225 level 04): its four
// risers' fits lean 2.4-5.2 deg (a nosing's front in each, multipath at each foot), each knowing its
// normal to about a degree by its noise, and its four treads agree with each other to 0.3 deg. The walls
// and the risers, two vertical families, set up 4-6 deg off in pitch; every rise came out 3 cm short
// (39 false steps in 8 frames). A riser may lean by design: the treads set the pitch.
TEST(PerceptionGravity, RisersThatLeanDoNotSetThePitchAgainstTheTreads) {
  const double pitch = 2.0;
  const Eigen::Vector3d Y = Eigen::Vector3d::UnitY();
  std::vector<Segment> segs = {face_at(pitch, -Y, 7368, 0.4, 0.6, 0.0009f, 2.4f),
                               face_at(pitch, Y, 7159, 0.4, 0.6, 0.0010f, 2.2f)};
  const double lean_deg[] = {2.4, 3.4, 4.2, 5.2};
  const size_t riser_cells[] = {341, 388, 505, 666};
  const float riser_rms[] = {0.0066f, 0.0051f, 0.0049f, 0.0044f}, riser_depth[] = {3.8f, 3.5f, 3.2f, 2.8f};
  for (const Segment& r : leaning_risers(pitch, lean_deg, riser_cells, 0.057, 0.5, riser_rms, riser_depth))
    segs.push_back(r);
  // Seen edge-on: 2.5-6 cm (standard deviation) along the view.
  const size_t tread_cells[] = {103, 168, 303, 254};
  const float tread_rms[] = {0.0019f, 0.0013f, 0.0007f, 0.0008f}, tread_depth[] = {3.6f, 3.3f, 3.0f, 2.7f};
  const double tread_along_m[] = {0.061, 0.062, 0.062, 0.025};
  for (int i = 0; i < 4; ++i)
    segs.push_back(tread_along_view(pitch, 0.1 * (i - 1.5), tread_cells[i], tread_along_m[i], 0.5, tread_rms[i],
                                    tread_depth[i]));
  const auto up = estimate_up(segs, GravityConfig{}, true_up(pitch - 0.5));
  ASSERT_TRUE(up.has_value());
  EXPECT_GT(up->dot(true_up(pitch)), std::cos(0.3 * M_PI / 180));
  // Risers taken for plumb faces (no lean allowed): their pitch wins, degrees off.
  GravityConfig plumb;
  plumb.riser_lean_deg = 0.01f;
  const auto leaning = estimate_up(segs, plumb, true_up(pitch - 0.5));
  ASSERT_TRUE(leaning.has_value());
  EXPECT_LT(leaning->dot(true_up(pitch)), std::cos(2.0 * M_PI / 180));
}

// A Kinect v2 robot on a flight, looking 4 deg up (seed 241 stairs 01): no tread in view, a side wall
// and the top landing's end wall, both plumb, and four risers 0.6-1.4 m off leaning 4.7-11.2 deg
// (multipath at their feet, the nosing's front in their fit) with three times the walls' cells. The
// risers x the side wall set the pitch 5-7 deg off and every rise came out 3 cm short (18 false steps
// in 7 frames); the two walls know it.
TEST(PerceptionGravity, TwoWallsSetThePitchAgainstRisersThatLean) {
  const double pitch = 3.9;
  const Eigen::Vector3d X = Eigen::Vector3d::UnitX(), Y = Eigen::Vector3d::UnitY();
  const Segment side_wall = face_at(pitch, -Y, 3179, 0.25, 0.5, 0.0012f, 2.5f);
  const Segment end_wall = face_at(pitch, -X, 3723, 0.3, 0.6, 0.0017f, 3.4f);
  const double lean_deg[] = {8.5, 4.7, 5.2, 11.2}, plumb_deg[] = {0, 0, 0, 0};
  const size_t cells[] = {5857, 3755, 1981, 951};
  const float rms[] = {0.0020f, 0.0030f, 0.0044f, 0.0054f}, depth[] = {0.59f, 0.88f, 1.15f, 1.43f};
  std::vector<Segment> segs = leaning_risers(pitch, lean_deg, cells, 0.045, 0.3, rms, depth);
  segs.push_back(side_wall);
  segs.push_back(end_wall);
  const auto up = estimate_up(segs, GravityConfig{}, true_up(pitch));
  ASSERT_TRUE(up.has_value());
  EXPECT_GT(up->dot(true_up(pitch)), std::cos(0.3 * M_PI / 180));
  // Faces 4.9 m off that a stereo camera fits to 2 cm rms, leaning 8 deg, are no walls that know up:
  // plumb risers and the side wall set it.
  std::vector<Segment> far = leaning_risers(pitch, plumb_deg, cells, 0.045, 0.3, rms, depth);
  far.push_back(side_wall);
  far.push_back(face_at(pitch, Eigen::AngleAxisd(-8.0 * M_PI / 180, Y) * Eigen::AngleAxisd(40 * M_PI / 180, Eigen::Vector3d::UnitZ()) * -X,
                        243, 0.19, 0.33, 0.0208f, 4.9f));
  const auto plumb = estimate_up(far, GravityConfig{}, true_up(pitch));
  ASSERT_TRUE(plumb.has_value());
  EXPECT_GT(plumb->dot(true_up(pitch)), std::cos(0.3 * M_PI / 180));
}

}  // namespace
}  // namespace stairs
