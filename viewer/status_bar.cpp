#include "viewer/status_bar.hpp"

#include "viewer/palette.hpp"

#include <opencv2/imgproc.hpp>

#include <cstdio>

namespace stairs::viewer {

const char* direction_name(Direction d) {
  switch (d) {
    case Direction::Up: return "up";
    case Direction::Down: return "down";
    case Direction::None: break;
  }
  return "none";
}

const char* tracking_name(TrackingState s) {
  switch (s) {
    case TrackingState::Ok: return "ok";
    case TrackingState::Lost: return "lost";
    case TrackingState::Relocalised: return "relocalised";
    case TrackingState::None: break;
  }
  return "none";
}

std::string status_text(const Observation* obs, const StairModel* model, const ViewStats& stats) {
  char buf[256];
  std::string s;
  if (stats.frame_index >= 0) {
    std::snprintf(buf, sizeof buf, "frame %lld", static_cast<long long>(stats.frame_index));
  } else {
    std::snprintf(buf, sizeof buf, "%.1f fps", stats.fps);
  }
  s += buf;
  if (obs) {
    std::snprintf(buf, sizeof buf, " | perception %.1f ms", obs->latency_ms);
    s += buf;
  }
  if (model) {
    std::snprintf(buf, sizeof buf, " tracker %.1f ms", model->update_latency_ms);
    s += buf;
  }
  if (stats.end_to_end_ms >= 0) {
    std::snprintf(buf, sizeof buf, " | end-to-end %.0f ms", stats.end_to_end_ms);
    s += buf;
  }
  const Direction dir = model ? model->direction : obs ? obs->direction : Direction::None;
  s += std::string(" | direction ") + direction_name(dir);
  if (obs) s += " | seen " + std::to_string(obs->steps.size());
  if (model) {
    size_t steps = 0;
    for (const Flight& f : model->flights) steps += f.steps.size();
    s += " | model " + std::to_string(steps) + " steps, " + std::to_string(model->flights.size()) + " flights";
    s += std::string(" | tracking ") + tracking_name(model->state);
  }
  if (obs && obs->camera.valid) {
    std::snprintf(buf, sizeof buf, " | pitch %.1f roll %.1f", obs->camera.pitch_deg, obs->camera.roll_deg);
    s += buf;
    if (obs->camera.height_m) {
      std::snprintf(buf, sizeof buf, " h %.2f m", *obs->camera.height_m);
      s += buf;
    }
  }
  return s;
}

void draw_status_bar(cv::Mat& bar, const std::string& text) {
  bar.setTo(cv::Scalar(20, 20, 20));
  cv::putText(bar, text, {6, bar.rows - 8}, cv::FONT_HERSHEY_SIMPLEX, 0.42, kTextColour, 1, cv::LINE_AA);
}

}  // namespace stairs::viewer
