// Status bar: frame rate, latency, direction, number of steps, tracking state.
#pragma once

#include "common/types.hpp"

#include <opencv2/core.hpp>

#include <string>

namespace stairs::viewer {

struct ViewStats {
  double fps = 0.0;          // views drawn per second (live) or 0 (headless)
  int64_t frame_index = -1;  // headless: frame number in the input, -1 = live
  double end_to_end_ms = -1.0;  // live: now - depth frame's utime when the observation arrived, <0 = unknown
};

// One line; shared by the bar and the terminal status line.
std::string status_text(const Observation* obs, const StairModel* model, const ViewStats& stats);
void draw_status_bar(cv::Mat& bar, const std::string& text);

const char* direction_name(Direction d);
const char* tracking_name(TrackingState s);

}  // namespace stairs::viewer
