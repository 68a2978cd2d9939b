// Headless renders by the stairs-viewer program: of a log holding hand-built
// observations and models (drawn as recorded), of a sample log (or frames of
// the simulator) through the in-process pipeline, and of one real frame.
#include "common/cloud.hpp"
#include "common/file_util.hpp"
#include "common/frame_source.hpp"
#include "common/lcm_bridge.hpp"
#include "common/lcm_log.hpp"
#include "pixels.hpp"
#include "run_program.hpp"
#include "scenes.hpp"
#include "viewer/config.hpp"
#include "viewer/image_panel.hpp"
#include "viewer/layout.hpp"

#ifdef STAIRS_TEST_WITH_SIM
#include "drivers/sim/render.hpp"
#include "drivers/sim/scene.hpp"
#include "drivers/sim/trajectory.hpp"
#endif

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using namespace stairs;
using namespace stairs::viewer;
using namespace stairs::viewer::test;

namespace {

fs::path scratch(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("stairs_viewer_" + std::to_string(::getpid())) / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string read_text(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// Depth, truth, observation and model for 5 frames; the model grows a step per
// frame. A corrupt observation sits in the middle.
fs::path write_recorded_log(const fs::path& dir) {
  const fs::path path = dir / "recorded.lcmlog";
  LogWriter log(path.string());
  GroundTruth truth;
  truth.scene = "hand-built";
  truth.flights = stair_model(6).flights;
  for (int i = 0; i < 5; ++i) {
    const int64_t t = 1'000'000 + 100'000 * i;
    const DepthImage img = flat_depth(640, 480, 1500, t, i);
    log.write_message("STAIRS_DEPTH", t, to_lcm(img, 1));
    GroundTruthFrame gt;
    gt.position_m = {-1.0, 0.0, 1.2};
    gt.orientation = stair_model(1).camera_orientation;
    log.write_message("STAIRS_GROUND_TRUTH", t, to_lcm(truth, gt, t, i));
    if (i == 2) {
      const std::string junk = "not an observation";
      log.write("STAIRS_OBSERVATION", t + 1, junk.data(), junk.size());
    }
    log.write_message("STAIRS_OBSERVATION", t + 2, to_lcm(simple_observation(img), t + 2));
    log.write_message("STAIRS_MODEL", t + 3, to_lcm(stair_model(i + 1), t + 3, t, i));
  }
  log.close();
  return path;
}

// Share of the tread quad's pixels (in the image panel) that show the tread colour.
double tread_cover(const cv::Mat& view) {
  const ViewerConfig cfg;
  const cv::Mat panel = view(layout(cfg).image);
  const DepthImage img = flat_depth(640, 480, 1500);
  const Observation obs = simple_observation(img);
  const Intrinsics K = scale_intrinsics(img.K, panel.cols, panel.rows);
  std::vector<cv::Point> quad;
  for (int c : {0, 1, 3, 2}) quad.push_back(*project_gravity_point(obs.planes[0].corners[c], level_camera(), K));
  cv::Mat inside(panel.size(), CV_8UC1, cv::Scalar(0));
  cv::fillConvexPoly(inside, quad, cv::Scalar(255));
  int in = 0, tinted = 0;
  for (int v = 0; v < panel.rows; ++v)
    for (int u = 0; u < panel.cols; ++u)
      if (inside.at<uint8_t>(v, u)) {
        ++in;
        tinted += tread_tinted(panel.at<cv::Vec3b>(v, u));
      }
  return in ? double(tinted) / in : 0.0;
}

}  // namespace

TEST(ViewerRender, RecordedLogToPngDirectory) {
  const fs::path dir = scratch("recorded_dir");
  const fs::path log = write_recorded_log(dir);
  ASSERT_EQ(run_viewer("--render " + log.string() + " --out " + (dir / "out").string(), (dir / "err").string()), 0)
      << read_text(dir / "err");
  const std::string err = read_text(dir / "err");
  EXPECT_NE(err.find("recorded observations"), std::string::npos) << err;
  EXPECT_NE(err.find("invalid"), std::string::npos) << "the corrupt observation is reported: " << err;
  const ViewerConfig cfg;
  const Layout l = layout(cfg);
  for (int i = 0; i < 5; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06d.png", i);
    const cv::Mat view = cv::imread((dir / "out" / name).string(), cv::IMREAD_COLOR);
    ASSERT_FALSE(view.empty()) << name;
    EXPECT_EQ(view.size(), l.size);
    EXPECT_GT(tread_cover(view), 0.95) << name;
    // The model of frame i has i + 1 steps: one riser each in the side view.
    EXPECT_EQ(riser_blobs(view(l.side)), i + 1) << name;
    if (i > 0) {  // frame 0's only step is the landing (amber)
      EXPECT_GT(count_pixels(view(l.top), tread_tinted), 300) << name;
    }
  }
  EXPECT_FALSE(fs::exists(dir / "out" / "frame_000005.png"));
}

TEST(ViewerRender, RecordedLogToOnePngAndVideo) {
  const fs::path dir = scratch("recorded_one");
  const fs::path log = write_recorded_log(dir);
  const std::string err = (dir / "err").string();
  ASSERT_EQ(run_viewer("--render " + log.string() + " --out " + (dir / "last.png").string(), err), 0)
      << read_text(err);
  ASSERT_EQ(run_viewer("--render " + log.string() + " --frame 1 --out " + (dir / "f1.png").string(), err), 0)
      << read_text(err);
  const ViewerConfig cfg;
  const Layout l = layout(cfg);
  const cv::Mat last = cv::imread((dir / "last.png").string()), f1 = cv::imread((dir / "f1.png").string());
  ASSERT_FALSE(last.empty());
  ASSERT_FALSE(f1.empty());
  EXPECT_EQ(riser_blobs(last(l.side)), 5);
  EXPECT_EQ(riser_blobs(f1(l.side)), 2);

  ASSERT_EQ(run_viewer("--render " + log.string() + " --out " + (dir / "v.mp4").string(), err), 0) << read_text(err);
  cv::VideoCapture video((dir / "v.mp4").string());
  ASSERT_TRUE(video.isOpened());
  int frames = 0;
  cv::Mat frame;
  while (video.read(frame)) {
    EXPECT_EQ(frame.size(), l.size);
    ++frames;
  }
  EXPECT_EQ(frames, 5);
}

TEST(ViewerRender, BadInputNamesTheFile) {
  const fs::path dir = scratch("bad");
  EXPECT_NE(run_viewer("--render /nonexistent/log.lcmlog --out " + (dir / "x.png").string(), (dir / "err").string()),
            0);
  EXPECT_NE(read_text(dir / "err").find("/nonexistent/log.lcmlog"), std::string::npos);
  {
    std::ofstream f(dir / "truncated.lcmlog", std::ios::binary);
    f << "\xED\xA1\xDA\x01garbage";
  }
  EXPECT_NE(run_viewer("--render " + (dir / "truncated.lcmlog").string() + " --out " + (dir / "x.png").string(),
                       (dir / "err").string()),
            0);
  EXPECT_NE(read_text(dir / "err").find("truncated.lcmlog"), std::string::npos) << read_text(dir / "err");
}

// Issue 18: --out FILE.gif would have become a directory; without a display the
// live window aborted inside Qt (exit 134). Both now fail cleanly and say what to do.
TEST(ViewerRender, UnwrittenFormatAndNoDisplayFailCleanly) {
  const fs::path dir = scratch("clean_errors");
  const std::string log = (fs::path(STAIRS_SOURCE_DIR) / "logs" / "up_handheld.lcmlog").string();
  EXPECT_EQ(run_viewer("--render " + log + " --out " + (dir / "x.gif").string(), (dir / "err").string()), 1);
  EXPECT_NE(read_text(dir / "err").find(".gif is not written"), std::string::npos) << read_text(dir / "err");
  EXPECT_FALSE(fs::exists(dir / "x.gif"));
  const int rc = std::system(("env -u DISPLAY -u WAYLAND_DISPLAY " + viewer_program() + " --max-fps 1 2>" +
                              (dir / "err").string()).c_str());
  EXPECT_TRUE(WIFEXITED(rc) && WEXITSTATUS(rc) == 1) << rc;
  const std::string err = read_text(dir / "err");
  EXPECT_NE(err.find("DISPLAY"), std::string::npos) << err;
  EXPECT_NE(err.find("--render"), std::string::npos) << err;
}

namespace {

// A sample log of the simulator, or one written here from frames of the stairs_sim library.
std::optional<fs::path> sample_log(const fs::path& dir) {
  const fs::path logs = fs::path(STAIRS_SOURCE_DIR) / "logs";
  if (fs::exists(logs / "up_handheld.lcmlog")) return logs / "up_handheld.lcmlog";
#ifdef STAIRS_TEST_WITH_SIM
  const sim::Scene scene = sim::make_preset("straight_up");
  const Intrinsics K{640, 480, 525.0, 525.0, 319.5, 239.5};
  sim::SensorModel sensor;
  sensor.perfect = true;
  sim::Renderer renderer(scene, K, sensor, 7);
  const sim::Trajectory trajectory(scene, sim::trajectory_defaults(sim::Carrier::HandHeld));
  const fs::path path = dir / "sim_up.lcmlog";
  LogWriter log(path.string());
  const GroundTruth truth = renderer.stair_truth();
  for (int i = 0; i < std::min(trajectory.frames(), 60); ++i) {
    const int64_t t = static_cast<int64_t>(trajectory.time_s(i) * 1e6);
    const DepthImage img = renderer.render(trajectory.pose(i), t, i);
    log.write_message("STAIRS_DEPTH", t, to_lcm(img, 1));
    log.write_message("STAIRS_GROUND_TRUTH", t, to_lcm(truth, renderer.truth(trajectory.pose(i), trajectory.time_s(i), img), t, i));
  }
  log.close();
  return path;
#else
  (void)dir;
  return std::nullopt;
#endif
}

// Pixels of a horizontal surface (tread, landing, floor) by the true camera
// orientation: the depth's normal, in the stair frame, points up.
cv::Mat horizontal_mask(const DepthImage& img, const GroundTruthFrame& truth, cv::Size size) {
  const int s = 4;
  cv::Mat mask(img.K.height, img.K.width, CV_8UC1, cv::Scalar(0));
  cv::Mat known(img.K.height, img.K.width, CV_8UC1, cv::Scalar(0));
  auto p = [&](int u, int v) { return back_project(img.K, u, v, img.metres(u, v)); };
  for (int v = s; v < img.K.height - s; ++v)
    for (int u = s; u < img.K.width - s; ++u) {
      if (img.metres(u - s, v) <= 0 || img.metres(u + s, v) <= 0 || img.metres(u, v - s) <= 0 ||
          img.metres(u, v + s) <= 0)
        continue;
      const Eigen::Vector3d n =
          (p(u, v + s) - p(u, v - s)).cross(p(u + s, v) - p(u - s, v)).cast<double>().normalized();
      known.at<uint8_t>(v, u) = 1;
      mask.at<uint8_t>(v, u) = std::abs((truth.orientation * n).z()) > 0.9 ? 255 : 128;
    }
  cv::Mat out;
  cv::resize(mask, out, size, 0, 0, cv::INTER_NEAREST);
  return out;  // 255 horizontal, 128 not, 0 unknown
}

}  // namespace

TEST(ViewerRender, SampleLogThroughThePipelineShowsTreadsOnTreads) {
  const fs::path dir = scratch("sample");
  const auto log = sample_log(dir);
  if (!log) GTEST_SKIP() << "no logs/up_handheld.lcmlog and stairs_sim not built";
  const std::string err = (dir / "err").string();
  ASSERT_EQ(run_viewer("--render " + log->string() + " --every 10 --max-frames 60 --out " + (dir / "out").string(), err),
            0)
      << read_text(err);
  const std::string text = read_text(err);
  if (text.find("without stairs_perception") != std::string::npos) GTEST_SKIP() << text;

  const ViewerConfig cfg;
  const Layout l = layout(cfg);
  auto source = open_frame_source(log->string());
  SourceFrame frame;
  int drawn = 0, tinted_total = 0, tinted_on_horizontal = 0, tinted_known = 0;
  for (int i = 0; i < 60 && source->next(frame); ++i) {
    if (i % 10) continue;
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06d.png", i);
    const cv::Mat view = cv::imread((dir / "out" / name).string());
    ASSERT_FALSE(view.empty()) << name;
    ASSERT_EQ(view.size(), l.size);
    ++drawn;
    ASSERT_TRUE(frame.truth) << "the sample log carries ground truth";
    const cv::Mat panel = view(l.image), horizontal = horizontal_mask(frame.image, *frame.truth, panel.size());
    for (int v = 0; v < panel.rows; ++v)
      for (int u = 0; u < panel.cols; ++u) {
        if (!tread_tinted(panel.at<cv::Vec3b>(v, u))) continue;
        ++tinted_total;
        const uint8_t h = horizontal.at<uint8_t>(v, u);
        tinted_known += h != 0;
        tinted_on_horizontal += h == 255;
      }
  }
  EXPECT_EQ(drawn, 6);
  // Perception found treads, and the viewer drew them where the horizontal surfaces are.
  EXPECT_GT(tinted_total, drawn * l.image.area() / 50) << "tread colour on < 2% of the image panels";
  ASSERT_GT(tinted_known, 0);
  EXPECT_GT(double(tinted_on_horizontal) / tinted_known, 0.8);
}

TEST(ViewerRender, OneRealFrame) {
  const std::string seq = STAIRS_REALDATA_DIR "/kinect2_lab_up";
  if (!fs::is_directory(seq)) GTEST_SKIP() << seq << " not present";
  const fs::path dir = scratch("real");
  ASSERT_EQ(run_viewer("--render " + seq + " --frame 1 --out " + (dir / "real.png").string(), (dir / "err").string()),
            0)
      << read_text(dir / "err");
  const cv::Mat view = cv::imread((dir / "real.png").string());
  const ViewerConfig cfg;
  ASSERT_EQ(view.size(), layout(cfg).size);
  // A 512x424 frame fitted into the panel: depth drawn (not the placeholder) over most of it.
  cv::Mat grey;
  cv::cvtColor(view(layout(cfg).image), grey, cv::COLOR_BGR2GRAY);
  EXPECT_GT(cv::countNonZero(grey > 60), layout(cfg).image.area() / 2);
}
