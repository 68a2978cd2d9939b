#include "viewer/side_view.hpp"

#include "viewer/palette.hpp"
#include "viewer/plot_frame.hpp"
#include "viewer/stair_geometry.hpp"

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <cstdio>

namespace stairs::viewer {

double forward_sign(const SceneRefs& scene) {
  auto cam = model_camera(scene.model);
  if (!cam) cam = truth_camera(scene.truth_frame);
  if (cam) return (cam->orientation * Eigen::Vector3d::UnitZ()).x() < 0 ? -1.0 : 1.0;
  if (scene.model && scene.model->direction == Direction::Down) return -1.0;
  return 1.0;
}

namespace {

void label(cv::Mat& panel, const std::string& text, cv::Point at, const cv::Scalar& colour) {
  cv::putText(panel, text, at, cv::FONT_HERSHEY_SIMPLEX, 0.38, colour, 1, cv::LINE_AA);
}

std::string cm(double m) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", m * 100.0);
  return buf;
}

// Camera dot, optical axis and the vertical field of view in the side view.
void draw_camera(cv::Mat& panel, const PlotFrame& pf, const CameraView& cam, double sign, const Intrinsics* K,
                 double ray_m, const cv::Scalar& colour, bool dashed) {
  auto side = [&](const Eigen::Vector3d& p) { return Eigen::Vector2d(sign * p.x(), p.z()); };
  const cv::Point c = pf.to_px(side(cam.position_m));
  const double t = std::tan(half_fov_rad(K, false));
  for (double dy : {-t, 0.0, t}) {
    Eigen::Vector2d d = side(cam.orientation * Eigen::Vector3d(0, dy, 1));
    if (d.norm() < 1e-6) continue;
    const cv::Point e = pf.to_px(side(cam.position_m) + d.normalized() * ray_m);
    if (dashed || dy == 0.0)
      draw_dashed_line(panel, c, e, colour, 1, 4.0);
    else
      cv::line(panel, c, e, colour, 1, cv::LINE_AA);
  }
  cv::circle(panel, c, 5, colour, dashed ? 1 : cv::FILLED, cv::LINE_AA);
}

}  // namespace

std::vector<ProfileSegment> draw_side_view(cv::Mat& panel, const SceneRefs& scene, const ViewerConfig& cfg) {
  panel.setTo(kBackground);
  const double sign = forward_sign(scene);
  auto side = [&](const Eigen::Vector2d& xz) { return Eigen::Vector2d(sign * xz.x(), xz.y()); };

  // Bounds of everything drawn, in (forward, up).
  Eigen::Vector2d lo(0, 0), hi(0, 0);
  auto extend = [&](const Eigen::Vector2d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  };
  auto extend_flights = [&](const std::vector<Flight>& flights) {
    for (const Flight& f : flights)
      for (const StepProfile& s : step_profiles(f)) {
        extend(side(s.riser_bottom));
        extend(side(s.tread_end));
      }
  };
  if (scene.model) extend_flights(scene.model->flights);
  if (scene.truth) extend_flights(scene.truth->flights);
  const auto cam = model_camera(scene.model), true_cam = truth_camera(scene.truth_frame);
  for (const auto& c : {cam, true_cam})
    if (c) extend({sign * c->position_m.x(), c->position_m.z()});
  const PlotFrame pf(lo, hi, panel.size(), cfg.view_margin_m, cfg.min_view_span_m);
  pf.draw_grid(panel, 0.5);

  std::vector<ProfileSegment> drawn;
  if (scene.truth)
    for (size_t f = 0; f < scene.truth->flights.size(); ++f) {
      const auto profiles = step_profiles(scene.truth->flights[f]);
      for (size_t i = 0; i < profiles.size(); ++i) {
        ProfileSegment seg{true, int(f), int(i), pf.to_px(side(profiles[i].riser_bottom)),
                           pf.to_px(side(profiles[i].nosing)), pf.to_px(side(profiles[i].tread_end))};
        draw_dashed_line(panel, seg.riser_bottom, seg.nosing, kTruthColour, 1);
        draw_dashed_line(panel, seg.nosing, seg.tread_end, kTruthColour, 1);
        drawn.push_back(seg);
      }
    }
  if (scene.model)
    for (size_t f = 0; f < scene.model->flights.size(); ++f) {
      const Flight& flight = scene.model->flights[f];
      const auto profiles = step_profiles(flight);
      for (size_t i = 0; i < profiles.size(); ++i) {
        const Step& step = flight.steps[i];
        ProfileSegment seg{false, int(f), int(i), pf.to_px(side(profiles[i].riser_bottom)),
                           pf.to_px(side(profiles[i].nosing)), pf.to_px(side(profiles[i].tread_end))};
        cv::line(panel, seg.riser_bottom, seg.nosing, kind_colour(PlaneKind::Riser), 2, cv::LINE_AA);
        cv::line(panel, seg.nosing, seg.tread_end, kind_colour(step.landing ? PlaneKind::Landing : PlaneKind::Tread), 2,
                 cv::LINE_AA);
        const cv::Point riser_mid = (seg.riser_bottom + seg.nosing) / 2, tread_mid = (seg.nosing + seg.tread_end) / 2;
        if (step.riser_height_m) label(panel, cm(*step.riser_height_m), riser_mid + cv::Point(-30, 4), kTextColour);
        if (step.tread_depth_m && !step.landing)
          label(panel, cm(*step.tread_depth_m), tread_mid + cv::Point(-10, 14), kTextColour);
        drawn.push_back(seg);
      }
    }
  if (true_cam) draw_camera(panel, pf, *true_cam, sign, scene.K, cfg.fov_ray_m, kTruthCameraColour, true);
  if (cam) draw_camera(panel, pf, *cam, sign, scene.K, cfg.fov_ray_m, kCameraColour, false);
  label(panel, sign > 0 ? "side: forward = stair +x (cm)" : "side: forward = stair -x (cm)", {6, 14}, kTextColour);
  return drawn;
}

}  // namespace stairs::viewer
