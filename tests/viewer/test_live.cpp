// Live mode under Xvfb: stairs-viewer opens its window and redraws it as
// messages arrive over real LCM (UDP multicast on loopback), checked on
// screenshots of the X server taken by this test (XGetImage).
#include "common/daemon.hpp"
#include "common/lcm_bridge.hpp"
#include "pixels.hpp"
#include "run_program.hpp"
#include "scenes.hpp"
#include "viewer/config.hpp"
#include "viewer/layout.hpp"
#include "xvfb.hpp"

#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <thread>

namespace fs = std::filesystem;
using namespace stairs;
using namespace stairs::viewer;
using namespace stairs::viewer::test;

namespace {

std::string read_text(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// Publishes depth, observation and a model of `steps` steps at 20 Hz for `seconds`.
void publish(lcm::LCM& lcm, int& seq, int steps, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    const int64_t t = now_utime();
    const DepthImage img = flat_depth(640, 480, 1500, t, seq++);
    const depth_frame_t d = to_lcm(img, 1);
    const stair_observation_t o = to_lcm(simple_observation(img), t);
    const stair_model_t m = to_lcm(stair_model(steps), t, img.utime, img.seq);
    lcm.publish("VIEWER_TEST_DEPTH", &d);
    lcm.publish("VIEWER_TEST_OBSERVATION", &o);
    lcm.publish("VIEWER_TEST_MODEL", &m);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
}

}  // namespace

TEST(ViewerLive, WindowUnderXvfbShowsAndUpdates) {
  Xvfb x;
  if (!x.running()) GTEST_SKIP() << "Xvfb cannot start: " << x.error();
  const cv::Mat blank = x.screenshot();

  const fs::path dir = fs::temp_directory_path() / ("stairs_viewer_live_" + std::to_string(getpid()));
  fs::create_directories(dir);
  std::mt19937 rng(std::random_device{}());
  const std::string url = "udpm://239.255.76.67:" + std::to_string(7700 + rng() % 200) + "?ttl=0";
  lcm::LCM lcm(url);
  ASSERT_TRUE(lcm.good()) << url;
  const pid_t viewer = spawn({viewer_program(), "--lcm-url", url, "--depth-channel", "VIEWER_TEST_DEPTH",
                              "--observation-channel", "VIEWER_TEST_OBSERVATION", "--model-channel",
                              "VIEWER_TEST_MODEL", "--screenshot", (dir / "own.png").string(), "--screenshot-after",
                              "5", "--verbose"},
                             x.display(), (dir / "err").string());
  ASSERT_GT(viewer, 0);
  std::this_thread::sleep_for(std::chrono::seconds(2));  // window up, subscribed

  int seq = 0;
  publish(lcm, seq, 2, 1.5);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const cv::Mat first = x.screenshot();
  publish(lcm, seq, 5, 1.5);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const cv::Mat second = x.screenshot();

  kill(viewer, SIGTERM);
  int status = 0;
  waitpid(viewer, &status, 0);
  const std::string err = read_text(dir / "err");
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << err;
  EXPECT_NE(err.find("stopped"), std::string::npos) << err;
  EXPECT_NE(err.find("fps"), std::string::npos) << "status line: " << err;

  // Not blank: the window covers a large part of the screen with varied content.
  const ViewerConfig cfg;
  const int window_area = layout(cfg).size.area();
  cv::Mat diff;
  cv::absdiff(first, blank, diff);
  cv::cvtColor(diff, diff, cv::COLOR_BGR2GRAY);
  EXPECT_GT(cv::countNonZero(diff), window_area / 2) << "the screen did not change: no window";
  EXPECT_GT(count_pixels(first, tread_tinted), 5000) << "no tread drawn in the window";
  // One riser in the image panel plus one per model step in the side view: it updated.
  EXPECT_EQ(riser_blobs(first), 1 + 2);
  EXPECT_EQ(riser_blobs(second), 1 + 5);
  cv::imwrite((dir / "screen_second.png").string(), second);

  const cv::Mat own = cv::imread((dir / "own.png").string());
  ASSERT_FALSE(own.empty()) << "--screenshot not written";
  EXPECT_EQ(own.size(), layout(cfg).size);
  fs::remove_all(dir);
}
