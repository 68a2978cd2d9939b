// Every parameter of the viewer's drawing, with its unit and default.
#pragma once

#include <cstddef>

namespace stairs::viewer {

struct ViewerConfig {
  // Panel sizes, px. The depth image is scaled to fit the image panel; the side
  // and top views share the right-hand column.
  int image_width_px = 640;
  int image_height_px = 480;
  int side_width_px = 480;
  int side_height_px = 300;
  int top_height_px = 180;
  int status_height_px = 26;
  // Depth colour map range, m (near = bright).
  double depth_min_m = 0.4;
  double depth_max_m = 4.5;
  double fill_alpha = 0.45;     // opacity of a plane's fill over the image, 0..1
  int normal_step_px = 2;       // neighbour offset for the normal image, px (of the depth image)
  double view_margin_m = 0.3;   // empty border around what the side/top views show, m
  double fov_ray_m = 2.0;       // length of the field-of-view rays drawn, m
  double min_view_span_m = 2.0; // smallest width/height the side/top views show, m
  size_t depth_history = 8;     // live mode: depth frames kept to match observations to
};

enum class ImageMode { Depth, Normals };

}  // namespace stairs::viewer
