#include "viewer/layout.hpp"

#include "viewer/image_panel.hpp"
#include "viewer/palette.hpp"
#include "viewer/top_view.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>

namespace stairs::viewer {

Layout layout(const ViewerConfig& cfg) {
  Layout l;
  const int right_h = cfg.side_height_px + cfg.top_height_px;
  const int body_h = std::max(cfg.image_height_px, right_h);
  l.image = {0, 0, cfg.image_width_px, cfg.image_height_px};
  l.side = {cfg.image_width_px, 0, cfg.side_width_px, cfg.side_height_px};
  l.top = {cfg.image_width_px, cfg.side_height_px, cfg.side_width_px, cfg.top_height_px};
  l.status = {0, body_h, cfg.image_width_px + cfg.side_width_px, cfg.status_height_px};
  l.size = {l.status.width, body_h + cfg.status_height_px};
  return l;
}

namespace {

size_t step_count(const StairModel* model) {
  size_t n = 0;
  if (model)
    for (const Flight& f : model->flights) n += f.steps.size();
  return n;
}

// Until the model has steps, the side and top views show the observation's steps
// in its own frame (the gravity-aligned camera frame, camera at the origin).
StairModel observation_as_model(const Observation& obs) {
  StairModel m;
  m.direction = obs.direction;
  Flight flight;
  flight.steps = obs.steps;
  std::sort(flight.steps.begin(), flight.steps.end(),
            [](const Step& a, const Step& b) { return a.nosing_m.z() < b.nosing_m.z(); });  // bottom to top
  m.flights.push_back(std::move(flight));
  m.camera_valid = obs.camera.valid;
  m.camera_orientation = obs.camera.gravity_rotation;
  return m;
}

}  // namespace

cv::Mat compose_view(const ViewInput& in, const ViewerConfig& cfg, std::vector<ProfileSegment>* segments) {
  const Layout l = layout(cfg);
  cv::Mat out(l.size, CV_8UC3, kBackground);
  image_panel(in.depth, in.observation, in.mode, cfg).copyTo(out(l.image));
  const bool from_observation = step_count(in.model) == 0 && in.observation && !in.observation->steps.empty();
  const StairModel obs_model = from_observation ? observation_as_model(*in.observation) : StairModel{};
  // The truth lives in the stair frame: it is not drawn over the observation's frame.
  const SceneRefs scene = from_observation
                              ? SceneRefs{&obs_model, nullptr, nullptr, in.depth ? &in.depth->K : nullptr}
                              : SceneRefs{in.model, in.truth, in.truth_frame, in.depth ? &in.depth->K : nullptr};
  cv::Mat side = out(l.side), top = out(l.top), bar = out(l.status);
  auto drawn = draw_side_view(side, scene, cfg);
  draw_top_view(top, scene, cfg);
  draw_status_bar(bar, status_text(in.observation, in.model, in.stats));
  if (from_observation)
    cv::putText(side, "(this frame's steps, camera frame)", {6, 30}, cv::FONT_HERSHEY_SIMPLEX, 0.38, kTextColour, 1,
                cv::LINE_AA);
  // Thin separators between the panels.
  cv::line(out, l.side.tl(), {l.side.x, l.top.br().y - 1}, kGridColour, 1);
  cv::line(out, l.top.tl(), {l.top.br().x - 1, l.top.y}, kGridColour, 1);
  if (segments) {
    for (auto& s : drawn)
      for (cv::Point* p : {&s.riser_bottom, &s.nosing, &s.tread_end}) *p += l.side.tl();
    *segments = std::move(drawn);
  }
  return out;
}

}  // namespace stairs::viewer
