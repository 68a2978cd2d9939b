// The drawing functions on hand-built values: no LCM, no display.
#include "common/cloud.hpp"
#include "pixels.hpp"
#include "scenes.hpp"
#include "viewer/frame_history.hpp"
#include "viewer/image_panel.hpp"
#include "viewer/layout.hpp"
#include "viewer/side_view.hpp"
#include "viewer/top_view.hpp"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

using namespace stairs;
using namespace stairs::viewer;
using namespace stairs::viewer::test;

TEST(ViewerImagePanel, ProjectionInvertsBackProjection) {
  const DepthImage img = flat_depth(640, 480, 1500);
  const Eigen::Quaterniond R = Eigen::AngleAxisd(-0.6, Eigen::Vector3d::UnitY()) * level_camera();
  for (const auto& [u, v] : {std::pair{10.f, 20.f}, {320.f, 240.f}, {600.f, 470.f}}) {
    const Eigen::Vector3f p_grav = R.cast<float>() * back_project(img.K, u, v, 1.7f);
    const auto px = project_gravity_point(p_grav, R, img.K);
    ASSERT_TRUE(px);
    EXPECT_NEAR(px->x, u, 1e-3);
    EXPECT_NEAR(px->y, v, 1e-3);
  }
  EXPECT_FALSE(project_gravity_point({-1.f, 0.f, 0.f}, level_camera(), img.K));  // behind the camera
}

TEST(ViewerImagePanel, TreadColourWhereTheTreadIs) {
  const ViewerConfig cfg;
  const DepthImage img = flat_depth(320, 240, 1500);  // half resolution: the panel scales it
  const Observation obs = simple_observation(img);
  const cv::Mat plain = image_panel(&img, nullptr, ImageMode::Depth, cfg);
  const cv::Mat panel = image_panel(&img, &obs, ImageMode::Depth, cfg);
  ASSERT_EQ(panel.size(), cv::Size(cfg.image_width_px, cfg.image_height_px));
  EXPECT_EQ(count_pixels(plain, tread_tinted), 0);  // the depth colour map is never tread-green

  // Where the tread's corners project at panel resolution.
  const Intrinsics K = scale_intrinsics(img.K, panel.cols, panel.rows);
  std::vector<cv::Point> quad;
  for (int c : {0, 1, 3, 2}) quad.push_back(*project_gravity_point(obs.planes[0].corners[c], level_camera(), K));
  cv::Mat inside(panel.size(), CV_8UC1, cv::Scalar(0));
  cv::fillConvexPoly(inside, quad, cv::Scalar(255));
  int in_tread = 0, in_total = 0, out_tread = 0;
  for (int v = 0; v < panel.rows; ++v)
    for (int u = 0; u < panel.cols; ++u) {
      const bool t = tread_tinted(panel.at<cv::Vec3b>(v, u));
      if (inside.at<uint8_t>(v, u)) {
        ++in_total;
        in_tread += t;
      } else {
        out_tread += t;
      }
    }
  ASSERT_GT(in_total, 1000);
  EXPECT_GT(in_tread, 0.95 * in_total);
  EXPECT_LT(out_tread, 0.05 * in_total);  // the outline's antialiased rim only
  // The tread lies below the horizon (row 240), the riser above it.
  const cv::Mat top = panel.rowRange(0, panel.rows / 2), bottom = panel.rowRange(panel.rows / 2, panel.rows);
  EXPECT_GT(count_pixels(top, riser_tinted), 500);
  EXPECT_EQ(count_pixels(top, tread_tinted), 0);
  EXPECT_EQ(count_pixels(bottom, riser_tinted), 0);
  // The convex edge, red, along the tread's far border.
  EXPECT_GT(count_pixels(panel, convex_red), 50);
}

TEST(ViewerImagePanel, NormalImageOfAFlatWallFacesTheCamera) {
  const ViewerConfig cfg;
  const DepthImage img = flat_depth(160, 120, 2000);
  const cv::Mat n = normal_colour(img, cfg);
  // A fronto-parallel wall: normal (0, 0, -1) everywhere inside the border -> (B, G, R) = (0, 127, 127).
  const cv::Vec3b p = n.at<cv::Vec3b>(60, 80);
  EXPECT_LE(p[0], 2);
  EXPECT_NEAR(p[1], 127, 2);
  EXPECT_NEAR(p[2], 127, 2);
  const cv::Mat panel = image_panel(&img, nullptr, ImageMode::Normals, cfg);
  EXPECT_EQ(panel.size(), cv::Size(cfg.image_width_px, cfg.image_height_px));
}

TEST(ViewerImagePanel, WithoutDepthSaysSo) {
  const ViewerConfig cfg;
  const cv::Mat panel = image_panel(nullptr, nullptr, ImageMode::Depth, cfg);
  EXPECT_EQ(panel.size(), cv::Size(cfg.image_width_px, cfg.image_height_px));
  EXPECT_GT(cv::countNonZero(panel.reshape(1) > 200), 50);  // the message's text
}

TEST(ViewerSideView, OneProfileSegmentPerModelStep) {
  const ViewerConfig cfg;
  for (int n : {1, 3, 6}) {
    const StairModel model = stair_model(n);
    cv::Mat panel(cfg.side_height_px, cfg.side_width_px, CV_8UC3);
    const auto segs = draw_side_view(panel, SceneRefs{&model, nullptr, nullptr, nullptr}, cfg);
    ASSERT_EQ(segs.size(), size_t(n));
    EXPECT_EQ(riser_blobs(panel), n) << n << " steps";
    for (size_t i = 0; i < segs.size(); ++i) {
      EXPECT_FALSE(segs[i].truth);
      // Going up the stair to the right: each riser goes up, each tread to the right.
      EXPECT_LT(segs[i].nosing.y, segs[i].riser_bottom.y);
      EXPECT_GT(segs[i].tread_end.x, segs[i].nosing.x);
      if (i > 0) {
        EXPECT_NEAR(segs[i].riser_bottom.y, segs[i - 1].nosing.y, 1);
      }
    }
    // Uniform scale: 0.17 m rise and 0.28 m going keep their ratio.
    const double rise_px = segs[0].riser_bottom.y - segs[0].nosing.y;
    if (n > 1) {
      EXPECT_NEAR((segs[1].nosing.x - segs[0].nosing.x) / rise_px, 0.28 / 0.17, 0.1);
    }
  }
}

TEST(ViewerSideView, TruthDashedAndDescendingDrawnForward) {
  const ViewerConfig cfg;
  StairModel model = stair_model(4);
  GroundTruth truth;
  truth.flights = stair_model(5).flights;
  cv::Mat panel(cfg.side_height_px, cfg.side_width_px, CV_8UC3);
  auto segs = draw_side_view(panel, SceneRefs{&model, &truth, nullptr, nullptr}, cfg);
  EXPECT_EQ(std::count_if(segs.begin(), segs.end(), [](const ProfileSegment& s) { return s.truth; }), 5);
  EXPECT_EQ(std::count_if(segs.begin(), segs.end(), [](const ProfileSegment& s) { return !s.truth; }), 4);

  // Camera at the top looking down the stair (-x): forward is still to the right,
  // so the profile descends to the right.
  model.camera_position_m = {2.0, 0.0, 1.9};
  model.camera_orientation = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()) * model.camera_orientation;
  segs = draw_side_view(panel, SceneRefs{&model, nullptr, nullptr, nullptr}, cfg);
  EXPECT_EQ(forward_sign(SceneRefs{&model, nullptr, nullptr, nullptr}), -1.0);
  ASSERT_EQ(segs.size(), 4u);
  EXPECT_LT(segs[1].nosing.x, segs[0].nosing.x);
  EXPECT_LT(segs[0].tread_end.x, segs[0].nosing.x);
}

TEST(ViewerTopView, OneFootprintPerStep) {
  const ViewerConfig cfg;
  const StairModel model = stair_model(5);
  cv::Mat panel(cfg.top_height_px, cfg.side_width_px, CV_8UC3);
  EXPECT_EQ(draw_top_view(panel, SceneRefs{&model, nullptr, nullptr, nullptr}, cfg), 5);
  EXPECT_GT(count_pixels(panel, tread_tinted), 500);
  cv::Mat empty(cfg.top_height_px, cfg.side_width_px, CV_8UC3);
  EXPECT_EQ(draw_top_view(empty, SceneRefs{}, cfg), 0);
  EXPECT_EQ(count_pixels(empty, tread_tinted), 0);
}

TEST(ViewerLayout, ComposesAllPanelsAtTheLayoutSize) {
  const ViewerConfig cfg;
  const DepthImage img = flat_depth(640, 480, 1500);
  const Observation obs = simple_observation(img);
  const StairModel model = stair_model(4);
  ViewInput in;
  in.depth = &img;
  in.observation = &obs;
  in.model = &model;
  std::vector<ProfileSegment> segs;
  const cv::Mat view = compose_view(in, cfg, &segs);
  const Layout l = layout(cfg);
  EXPECT_EQ(view.size(), l.size);
  EXPECT_EQ(segs.size(), 4u);
  for (const auto& s : segs) EXPECT_TRUE(l.side.contains(s.nosing));
  EXPECT_GT(count_pixels(view(l.image), tread_tinted), 1000);
  EXPECT_GT(count_pixels(view(l.top), tread_tinted), 500);
  EXPECT_GT(cv::countNonZero(view(l.status).reshape(1) > 200), 100);  // text
  const std::string text = status_text(&obs, &model, {});
  EXPECT_NE(text.find("tracking ok"), std::string::npos) << text;
  EXPECT_NE(text.find("model 4 steps"), std::string::npos) << text;
  EXPECT_NE(text.find("direction up"), std::string::npos) << text;
}

TEST(ViewerLayout, ObservationStepsShownUntilTheModelHasSome) {
  const ViewerConfig cfg;
  const DepthImage img = flat_depth(640, 480, 1500);
  const Observation obs = simple_observation(img);
  const StairModel empty;
  ViewInput in;
  in.depth = &img;
  in.observation = &obs;
  in.model = &empty;
  std::vector<ProfileSegment> segs;
  compose_view(in, cfg, &segs);
  EXPECT_EQ(segs.size(), obs.steps.size());
}

TEST(ViewerFrameHistory, KeepsTheLastFramesAndFindsByStamp) {
  FrameHistory h(3);
  for (int i = 0; i < 5; ++i) h.push(flat_depth(4, 3, 1000, 100 * i, i));
  EXPECT_EQ(h.size(), 3u);
  EXPECT_EQ(h.find(100, 1), nullptr);  // pushed out
  ASSERT_NE(h.find(300, 3), nullptr);
  EXPECT_EQ(h.find(300, 3)->seq, 3);
  EXPECT_EQ(h.find(300, 4), nullptr);  // seq must match too
  EXPECT_EQ(h.latest()->seq, 4);
}
