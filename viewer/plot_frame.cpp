#include "viewer/plot_frame.hpp"

#include "viewer/palette.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace stairs::viewer {

PlotFrame::PlotFrame(const Eigen::Vector2d& min_m, const Eigen::Vector2d& max_m, cv::Size size, double margin_m,
                     double min_span_m)
    : height_px_(size.height) {
  Eigen::Vector2d lo = min_m.array() - margin_m, hi = max_m.array() + margin_m;
  for (int i = 0; i < 2; ++i) {  // never zoom in further than min_span_m
    const double grow = std::max(0.0, min_span_m - (hi[i] - lo[i])) / 2.0;
    lo[i] -= grow;
    hi[i] += grow;
  }
  scale_ = std::min(size.width / (hi.x() - lo.x()), size.height / (hi.y() - lo.y()));
  // Centre the fitted box in the panel.
  const Eigen::Vector2d span_m(size.width / scale_, size.height / scale_);
  origin_m_ = (lo + hi) / 2.0 - span_m / 2.0;
}

cv::Point PlotFrame::to_px(const Eigen::Vector2d& p_m) const {
  const Eigen::Vector2d d = (p_m - origin_m_) * scale_;
  return {static_cast<int>(std::lround(d.x())), static_cast<int>(std::lround(height_px_ - 1 - d.y()))};
}

void PlotFrame::draw_grid(cv::Mat& panel, double step_m) const {
  const double x0 = std::floor(origin_m_.x() / step_m) * step_m;
  const double y0 = std::floor(origin_m_.y() / step_m) * step_m;
  const double x1 = origin_m_.x() + panel.cols / scale_, y1 = origin_m_.y() + panel.rows / scale_;
  for (double x = x0; x <= x1; x += step_m) {
    const int u = to_px({x, 0}).x;
    cv::line(panel, {u, 0}, {u, panel.rows - 1}, kGridColour, 1);
  }
  for (double y = y0; y <= y1; y += step_m) {
    const int v = to_px({0, y}).y;
    cv::line(panel, {0, v}, {panel.cols - 1, v}, kGridColour, 1);
  }
}

void draw_dashed_line(cv::Mat& img, cv::Point a, cv::Point b, const cv::Scalar& colour, int thickness,
                      double dash_px) {
  const cv::Point2d d = b - a;
  const double len = std::hypot(d.x, d.y);
  if (len < 1.0) return;
  for (double s = 0.0; s < len; s += 2.0 * dash_px) {
    const double e = std::min(len, s + dash_px);
    const cv::Point2d p0 = cv::Point2d(a) + d * (s / len), p1 = cv::Point2d(a) + d * (e / len);
    cv::line(img, cv::Point(cvRound(p0.x), cvRound(p0.y)), cv::Point(cvRound(p1.x), cvRound(p1.y)), colour,
             thickness, cv::LINE_AA);
  }
}

}  // namespace stairs::viewer
