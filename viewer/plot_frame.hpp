// A metric 2-D view (side or top) mapped to a panel: uniform scale, fitted to
// the bounds of what is drawn, plus the line styles both views use.
#pragma once

#include <opencv2/core.hpp>

#include <Eigen/Core>

namespace stairs::viewer {

class PlotFrame {
 public:
  // Fits [min, max] (m, x right, y up) plus margin into a panel of `size`.
  PlotFrame(const Eigen::Vector2d& min_m, const Eigen::Vector2d& max_m, cv::Size size, double margin_m,
            double min_span_m);
  cv::Point to_px(const Eigen::Vector2d& p_m) const;
  double px_per_m() const { return scale_; }
  // Faint grid lines every `step_m`.
  void draw_grid(cv::Mat& panel, double step_m) const;

 private:
  Eigen::Vector2d origin_m_;  // metric point at the panel's bottom-left
  double scale_ = 1.0;        // px per m
  int height_px_ = 0;
};

void draw_dashed_line(cv::Mat& img, cv::Point a, cv::Point b, const cv::Scalar& colour, int thickness,
                      double dash_px = 6.0);

}  // namespace stairs::viewer
