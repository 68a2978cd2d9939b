// Headless mode: draws the viewer's panels for every frame of a log or a
// sequence directory into PNGs, a video, or one PNG.
#include "viewer/app.hpp"

#include "chain/offline_chain.hpp"
#include "common/frame_source.hpp"
#include "common/lcm_log.hpp"
#include "viewer/layout.hpp"
#include "viewer/view_state.hpp"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <iostream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace stairs::viewer {

namespace {

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// Where the drawn views go: a directory of PNGs, a video, or one PNG.
class Sink {
 public:
  Sink(std::string out, double fps) : out_(std::move(out)), fps_(fps) {
    if (is_png()) {
      if (fs::path(out_).has_parent_path()) fs::create_directories(fs::path(out_).parent_path());
    } else if (!is_video()) {
      fs::create_directories(out_);
    }
  }
  void add(const cv::Mat& view, int64_t index) {
    ++written_;
    if (is_png()) {
      last_ = view.clone();
    } else if (is_video()) {
      if (!video_.isOpened()) {
        const int fourcc = ends_with(out_, ".avi") ? cv::VideoWriter::fourcc('M', 'J', 'P', 'G')
                                                   : cv::VideoWriter::fourcc('m', 'p', '4', 'v');
        if (!video_.open(out_, fourcc, fps_, view.size()))
          throw std::runtime_error(out_ + ": cannot open a video writer (mp4v/MJPG)");
      }
      video_.write(view);
    } else {
      char name[32];
      std::snprintf(name, sizeof name, "frame_%06lld.png", static_cast<long long>(index));
      write_png((fs::path(out_) / name).string(), view);
    }
  }
  void finish() {
    if (is_png() && !last_.empty()) write_png(out_, last_);
    video_.release();
  }
  int64_t written() const { return written_; }

 private:
  bool is_png() const { return ends_with(out_, ".png"); }
  bool is_video() const { return ends_with(out_, ".mp4") || ends_with(out_, ".avi"); }
  static void write_png(const std::string& path, const cv::Mat& img) {
    if (!cv::imwrite(path, img, {cv::IMWRITE_PNG_COMPRESSION, 9})) throw std::runtime_error(path + ": cannot write");
  }
  std::string out_;
  double fps_;
  cv::VideoWriter video_;
  cv::Mat last_;
  int64_t written_ = 0;
};

// Which input frames to draw: --frame N, or every K-th up to --max-frames.
struct Selection {
  int64_t only = -1, every = 1, max_frames = 0;
  bool draw(int64_t i) const { return only >= 0 ? i == only : i % every == 0; }
  bool done(int64_t i) const { return (only >= 0 && i >= only) || (max_frames > 0 && i + 1 >= max_frames); }
};

bool log_has_channel(const std::string& path, const std::string& channel) {
  LogReader log(path);
  LogEvent ev;
  while (log.next(ev))
    if (ev.channel == channel) return true;
  return false;
}

// A log that already holds observations (and models): one view per observation,
// drawn once the model made from it (or the next observation) arrives.
int64_t render_recorded(const std::string& path, const Channels& ch, const Selection& sel, ImageMode mode,
                        const ViewerConfig& cfg, Sink& sink) {
  ViewState state(ch, cfg.depth_history);
  LogReader log(path);
  LogEvent ev;
  int64_t index = -1, invalid = 0;
  bool pending = false;
  auto flush = [&] {
    if (pending && sel.draw(index)) {
      ViewStats stats;
      stats.frame_index = index;
      sink.add(compose_view(state.view(mode, stats), cfg), index);
    }
    pending = false;
  };
  while (log.next(ev)) {
    if (ev.channel == ch.observation && pending) {
      flush();
      if (sel.done(index)) break;
    }
    std::string error;
    const MessageKind kind = state.handle(ev.channel, ev.data.data(), ev.data.size(), error);
    if (!error.empty()) {
      if (invalid++ < 5) std::cerr << "stairs-viewer: " << path << ": skipped " << ev.channel << ": " << error << "\n";
      continue;
    }
    if (kind == MessageKind::Observation) {
      ++index;
      pending = true;
    } else if (kind == MessageKind::Model && pending) {
      flush();
      if (sel.done(index)) break;
    }
  }
  flush();
  if (invalid) std::cerr << "stairs-viewer: " << path << ": " << invalid << " invalid messages skipped\n";
  return index + 1;
}

// Depth frames only: perception and the tracker run here, in-process.
int64_t render_pipeline(const Options& opts, const std::string& input, const Channels& ch, const Selection& sel,
                        ImageMode mode, const ViewerConfig& cfg, Sink& sink) {
  auto source = open_frame_source(input, ch.depth, ch.truth);
  OfflineChain chain(load_chain_config(opts.get("config")));
  SourceFrame frame;
  int64_t index = 0;
  for (; source->next(frame); ++index) {
    chain.add_inputs(frame);
    const ChainStep step = chain.process(frame.image);
    if (sel.draw(index)) {
      ViewInput in;
      in.depth = &frame.image;
      in.observation = &step.observation;
      in.model = step.model;
      in.truth = source->ground_truth() ? &*source->ground_truth() : nullptr;
      in.truth_frame = frame.truth ? &*frame.truth : nullptr;
      in.mode = mode;
      in.stats.frame_index = index;
      sink.add(compose_view(in, cfg), index);
    }
    if (sel.done(index)) {
      ++index;
      break;
    }
  }
  if (source->invalid())
    std::cerr << "stairs-viewer: " << input << ": " << source->invalid() << " invalid depth frames skipped ("
              << source->last_error() << ")\n";
  return index;
}

}  // namespace

int run_render(const Options& opts) {
  const std::string input = opts.get("render"), out = opts.get("out");
  if (out.empty()) throw std::runtime_error("--render needs --out DIR|FILE.mp4|FILE.png");
  // A file name with another image or video extension would silently become a directory.
  const std::string ext = fs::path(out).extension().string();
  static const char* const kNotWritten[] = {".gif", ".jpg", ".jpeg", ".bmp", ".tif", ".tiff", ".webp", ".mkv", ".mov", ".webm"};
  if (std::find(std::begin(kNotWritten), std::end(kNotWritten), ext) != std::end(kNotWritten))
    throw std::runtime_error("--out '" + out + "': " + ext + " is not written; give a directory (one PNG per frame), "
                             "FILE.mp4, FILE.avi or FILE.png");
  if (!fs::exists(input)) throw std::runtime_error(input + ": no such file or directory");
  const Channels ch{opts.get("depth-channel"), opts.get("observation-channel"), opts.get("model-channel"),
                    opts.get("truth-channel")};
  Selection sel;
  if (opts.has("frame")) sel.only = opts.get_int("frame");
  sel.every = std::max(1, opts.get_int("every"));
  sel.max_frames = opts.get_int("max-frames");
  const ImageMode mode = opts.flag("normals") ? ImageMode::Normals : ImageMode::Depth;
  const ViewerConfig cfg;
  Sink sink(out, opts.get_double("video-fps"));
  const bool recorded = fs::is_regular_file(input) && log_has_channel(input, ch.observation);
  const int64_t frames = recorded ? render_recorded(input, ch, sel, mode, cfg, sink)
                                  : render_pipeline(opts, input, ch, sel, mode, cfg, sink);
  sink.finish();
  if (sink.written() == 0)
    throw std::runtime_error(input + ": nothing drawn (" + std::to_string(frames) + " frames" +
                             (sel.only >= 0 ? ", --frame " + std::to_string(sel.only) : std::string()) + ")");
  std::cerr << "stairs-viewer: " << input << ": " << frames << " frames read ("
            << (recorded ? "recorded observations" : "in-process pipeline") << "), " << sink.written()
            << " views written to " << out << "\n";
  return 0;
}

}  // namespace stairs::viewer
