#include "viewer/top_view.hpp"

#include "viewer/palette.hpp"
#include "viewer/plot_frame.hpp"
#include "viewer/stair_geometry.hpp"

#include <opencv2/imgproc.hpp>

#include <array>
#include <cmath>

namespace stairs::viewer {

namespace {

constexpr double kUnknownWidthM = 1.0;  // drawn width of a step whose width is unknown

// Tread footprint corners in (forward, left), m.
std::array<Eigen::Vector2d, 4> footprint(const Step& s, double flight_width_m, double sign) {
  const double w = s.width_m > 0 ? s.width_m : flight_width_m > 0 ? flight_width_m : kUnknownWidthM;
  const double x0 = s.nosing_m.x(), x1 = x0 + s.tread_depth_m.value_or(0.0);
  const double y0 = s.nosing_m.y() - w / 2, y1 = s.nosing_m.y() + w / 2;
  return {{{sign * x0, y0}, {sign * x1, y0}, {sign * x1, y1}, {sign * x0, y1}}};
}

}  // namespace

int draw_top_view(cv::Mat& panel, const SceneRefs& scene, const ViewerConfig& cfg) {
  panel.setTo(kBackground);
  const double sign = forward_sign(scene);
  Eigen::Vector2d lo(0, 0), hi(0, 0);
  auto extend_flights = [&](const std::vector<Flight>& flights) {
    for (const Flight& f : flights)
      for (const Step& s : f.steps)
        for (const auto& p : footprint(s, f.width_m, sign)) {
          lo = lo.cwiseMin(p);
          hi = hi.cwiseMax(p);
        }
  };
  if (scene.model) extend_flights(scene.model->flights);
  if (scene.truth) extend_flights(scene.truth->flights);
  const auto cam = model_camera(scene.model), true_cam = truth_camera(scene.truth_frame);
  for (const auto& c : {cam, true_cam})
    if (c) {
      const Eigen::Vector2d p(sign * c->position_m.x(), c->position_m.y());
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  const PlotFrame pf(lo, hi, panel.size(), cfg.view_margin_m, cfg.min_view_span_m);
  pf.draw_grid(panel, 0.5);
  auto to_px = [&](const std::array<Eigen::Vector2d, 4>& c) {
    std::vector<cv::Point> px;
    for (const auto& p : c) px.push_back(pf.to_px(p));
    return px;
  };

  int treads = 0;
  if (scene.model)
    for (const Flight& f : scene.model->flights)
      for (const Step& s : f.steps) {
        const auto px = to_px(footprint(s, f.width_m, sign));
        const cv::Scalar colour = kind_colour(s.landing ? PlaneKind::Landing : PlaneKind::Tread);
        cv::fillConvexPoly(panel, px, colour * 0.6, cv::LINE_AA);
        cv::polylines(panel, px, true, colour, 1, cv::LINE_AA);
        ++treads;
      }
  if (scene.truth)
    for (const Flight& f : scene.truth->flights)
      for (const Step& s : f.steps) {
        const auto px = to_px(footprint(s, f.width_m, sign));
        for (size_t i = 0; i < px.size(); ++i) draw_dashed_line(panel, px[i], px[(i + 1) % px.size()], kTruthColour, 1);
      }
  const double t = std::tan(half_fov_rad(scene.K, true));
  for (const auto& [c, colour] : {std::pair{true_cam, kTruthCameraColour}, std::pair{cam, kCameraColour}}) {
    if (!c) continue;
    const Eigen::Vector2d o(sign * c->position_m.x(), c->position_m.y());
    for (double dx : {-t, t}) {
      const Eigen::Vector3d d3 = c->orientation * Eigen::Vector3d(dx, 0, 1);
      Eigen::Vector2d d(sign * d3.x(), d3.y());
      if (d.norm() < 1e-6) continue;
      cv::line(panel, pf.to_px(o), pf.to_px(o + d.normalized() * cfg.fov_ray_m), colour, 1, cv::LINE_AA);
    }
    cv::circle(panel, pf.to_px(o), 4, colour, cv::FILLED, cv::LINE_AA);
  }
  cv::putText(panel, "top: forward right, left up", {6, 14}, cv::FONT_HERSHEY_SIMPLEX, 0.38, kTextColour, 1,
              cv::LINE_AA);
  return treads;
}

}  // namespace stairs::viewer
