// Live mode: one window over LCM, redrawn when something new arrives.
#include "viewer/app.hpp"

#include "viewer/layout.hpp"
#include "viewer/view_state.hpp"

#include <lcm/lcm-cpp.hpp>
#include <opencv2/highgui.hpp>
#include <opencv2/imgcodecs.hpp>

#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <cstdio>
#include <iostream>
#include <stdexcept>

namespace stairs::viewer {

namespace {

using Clock = std::chrono::steady_clock;

struct Counters {
  int64_t depth = 0, observations = 0, models = 0, truth = 0, invalid = 0, updates = 0;
};

class LiveViewer {
 public:
  LiveViewer(const Channels& ch, const ViewerConfig& cfg) : state_(ch, cfg.depth_history) {}

  void on_message(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
    std::string error;
    switch (state_.handle(channel, rbuf->data, rbuf->data_size, error)) {
      case MessageKind::Depth: ++counters_.depth; break;
      case MessageKind::Observation:
        ++counters_.observations;
        end_to_end_ms_ = (now_utime() - state_.observation()->source_utime) / 1e3;
        break;
      case MessageKind::Model: ++counters_.models; break;
      case MessageKind::Truth: ++counters_.truth; break;
      case MessageKind::Unknown:
        ++counters_.invalid;
        last_error_ = channel + ": " + error;
        if (Clock::now() - last_error_log_ > std::chrono::seconds(1)) {  // at most one line a second
          std::cerr << "stairs-viewer: rejected " << last_error_ << " (" << counters_.invalid << " so far)\n";
          last_error_log_ = Clock::now();
        }
        return;
    }
    dirty_ = true;
  }

  bool dirty() const { return dirty_; }
  void touch() { dirty_ = true; }
  Counters& counters() { return counters_; }

  cv::Mat draw(ImageMode mode, double fps, const ViewerConfig& cfg) {
    dirty_ = false;
    ++counters_.updates;
    ViewStats stats;
    stats.fps = fps;
    // A replayed log carries old timestamps: show the end-to-end latency only when it is plausible.
    if (end_to_end_ms_ >= 0 && end_to_end_ms_ < 10'000) stats.end_to_end_ms = end_to_end_ms_;
    return compose_view(state_.view(mode, stats), cfg);
  }

  std::string status_line(double fps) const {
    ViewStats stats;
    stats.fps = fps;
    const ViewInput in = state_.view(ImageMode::Depth, stats);
    char buf[160];
    std::snprintf(buf, sizeof buf, "stairs-viewer: %lld depth, %lld obs, %lld models, %lld invalid | ",
                  static_cast<long long>(counters_.depth), static_cast<long long>(counters_.observations),
                  static_cast<long long>(counters_.models), static_cast<long long>(counters_.invalid));
    return buf + status_text(in.observation, in.model, stats);
  }

 private:
  ViewState state_;
  Counters counters_;
  bool dirty_ = true;  // draw the empty window once at start
  double end_to_end_ms_ = -1.0;
  std::string last_error_;
  Clock::time_point last_error_log_{};
};

}  // namespace

int run_live(const Options& opts) {
  // Without a display Qt aborts inside the first window (exit 134): say why first.
  const char* x11 = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((!x11 || !*x11) && (!wayland || !*wayland))
    throw std::runtime_error("no display: DISPLAY (or WAYLAND_DISPLAY) is not set. For pictures without one, use "
                             "--render LOG --out DIR|FILE.mp4|FILE.png");
  const Channels ch{opts.get("depth-channel"), opts.get("observation-channel"), opts.get("model-channel"),
                    opts.get("truth-channel")};
  const ViewerConfig cfg;
  lcm::LCM lcm(opts.get("lcm-url"));
  if (!lcm.good()) throw std::runtime_error("cannot open LCM at '" + opts.get("lcm-url") + "'");
  LiveViewer viewer(ch, cfg);
  for (const std::string& c : {ch.depth, ch.observation, ch.model, ch.truth})
    lcm.subscribe(c, &LiveViewer::on_message, &viewer);

  const std::string window = opts.get("window"), screenshot = opts.get("screenshot");
  const int64_t screenshot_after = opts.get_int("screenshot-after"), exit_after = opts.get_int("exit-after");
  const auto min_period = std::chrono::duration<double>(1.0 / std::max(1.0, opts.get_double("max-fps")));
  const bool print_status = isatty(STDERR_FILENO) || opts.flag("verbose");
  ImageMode mode = opts.flag("normals") ? ImageMode::Normals : ImageMode::Depth;

  install_stop_signals();
  cv::namedWindow(window, cv::WINDOW_AUTOSIZE | cv::WINDOW_GUI_NORMAL);
  auto last_draw = Clock::now() - std::chrono::hours(1), last_status = Clock::now();
  int64_t updates_at_status = 0;
  double fps = 0.0;
  bool shown = false;
  while (!stop_requested()) {
    // Drain what has arrived, waiting a little when nothing has.
    for (int n = 0; lcm.handleTimeout(n == 0 ? 10 : 0) > 0 && n < 1000; ++n) {
    }
    const auto now = Clock::now();
    if (viewer.dirty() && now - last_draw >= min_period) {
      const cv::Mat view = viewer.draw(mode, fps, cfg);
      cv::imshow(window, view);
      shown = true;
      last_draw = now;
      const int64_t updates = viewer.counters().updates;
      if (!screenshot.empty() && updates == screenshot_after && !cv::imwrite(screenshot, view))
        std::cerr << "stairs-viewer: " << screenshot << ": cannot write the screenshot\n";
      if (exit_after > 0 && updates >= exit_after) break;
    }
    const int key = cv::waitKey(1);
    if (key == 'q' || key == 27) break;
    if (key == 'n') {
      mode = mode == ImageMode::Depth ? ImageMode::Normals : ImageMode::Depth;
      viewer.touch();
    }
    if (shown && cv::getWindowProperty(window, cv::WND_PROP_VISIBLE) < 1) break;  // closed by the user
    const double dt = std::chrono::duration<double>(Clock::now() - last_status).count();
    if (dt >= 1.0) {
      fps = (viewer.counters().updates - updates_at_status) / dt;
      updates_at_status = viewer.counters().updates;
      last_status = Clock::now();
      if (print_status) std::cerr << viewer.status_line(fps) << "\n";
    }
  }
  cv::destroyAllWindows();
  const Counters& c = viewer.counters();
  std::fprintf(stderr, "stairs-viewer: stopped: %lld depth, %lld observations, %lld models, %lld invalid, %lld updates\n",
               static_cast<long long>(c.depth), static_cast<long long>(c.observations),
               static_cast<long long>(c.models), static_cast<long long>(c.invalid),
               static_cast<long long>(c.updates));
  return 0;
}

}  // namespace stairs::viewer
