// stairs-openni2 as a subprocess: no device -> one line and a non-zero exit;
// an .oni written by OniWriter -> the same frames out (log and udpm), status
// on STAIRS_STATUS, a clean stop on SIGTERM.
#include "tests/support/daemon_process.hpp"
#include "tests/support/multicast.hpp"
#include "common/lcm_bridge.hpp"
#include "common/lcm_log.hpp"
#include "drivers/openni2/oni_writer.hpp"
#ifdef STAIRS_HAVE_SIM
#include "drivers/sim/render.hpp"
#include "drivers/sim/scene.hpp"
#include "drivers/sim/trajectory.hpp"
#endif

#include <OpenNI.h>
#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

extern char** environ;

using namespace stairs;

namespace {

const std::string kProgram = std::string(STAIRS_BINARY_DIR) + "/bin/stairs-openni2";

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("stairs_openni2_drv_" + std::to_string(getpid()) + "_" + name))
      .string();
}

// Starts the program with stdout+stderr to `out_file`.
pid_t spawn(std::vector<std::string> args, const std::string& out_file) {
  args.insert(args.begin(), kProgram);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, kProgram.c_str(), &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  return rc == 0 ? pid : -1;
}

std::string slurp(const std::string& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

struct RunResult {
  int code;
  std::string output;
};
RunResult run(const std::vector<std::string>& args, double timeout_s = 30) {
  const std::string out = temp_path("out.txt");
  const pid_t pid = spawn(args, out);
  EXPECT_GT(pid, 0);
  RunResult r{pid > 0 ? stairs::test::wait_exit(pid, timeout_s) : -1, slurp(out)};
  std::remove(out.c_str());
  return r;
}

int count_lines(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

// Frames of a stair (stairs_sim when built, else a synthetic staircase-like ramp).
std::vector<DepthImage> source_frames(int w, int h, int n) {
  std::vector<DepthImage> frames;
  Intrinsics K{w, h, 0.5 * w / std::tan(0.5 * 1.0144686), 0.5 * h / std::tan(0.5 * 0.7898094), (w - 1) / 2.0,
               (h - 1) / 2.0};
#ifdef STAIRS_HAVE_SIM
  const sim::Scene scene = sim::make_preset("straight_up");
  sim::Renderer renderer(scene, K, sim::SensorModel{}, 7);  // every Kinect effect on: noisy, holes
  const sim::Trajectory traj(scene, sim::trajectory_defaults(sim::Carrier::HandHeld));
  for (int i = 0; i < n; ++i)
    frames.push_back(renderer.render(traj.pose(i % traj.frames()), 1'700'000'000'000'000 + i * 33'333, i));
#else
  for (int i = 0; i < n; ++i) {
    DepthImage img;
    img.K = K;
    img.utime = 1'700'000'000'000'000 + i * 33'333;
    img.seq = i;
    img.depth.resize(static_cast<size_t>(w) * h);
    for (int v = 0; v < h; ++v)
      for (int u = 0; u < w; ++u)  // steps: depth jumps every 40 rows, holes on a diagonal
        img.depth[static_cast<size_t>(v) * w + u] =
            static_cast<uint16_t>((u + v + i) % 97 == 0 ? 0 : 900 + 300 * ((h - v) / 40) + (u % 17) + i);
    frames.push_back(img);
  }
#endif
  return frames;
}

std::string write_oni(const std::vector<DepthImage>& frames, const std::string& name) {
  const std::string path = temp_path(name);
  OniWriter w(path, frames[0].K.width, frames[0].K.height, 30);
  for (const auto& f : frames) w.write(f);
  w.close();
  return path;
}

void expect_same_frames(const std::vector<depth_frame_t>& got, const std::vector<DepthImage>& sent) {
  ASSERT_EQ(got.size(), sent.size());
  for (size_t i = 0; i < got.size(); ++i) {
    DepthImage img;
    std::string error;
    ASSERT_TRUE(from_lcm(got[i], img, error)) << error;
    EXPECT_EQ(img.seq, static_cast<int>(i));
    EXPECT_TRUE(img.depth == sent[i].depth) << "frame " << i << " depth differs";
    EXPECT_NEAR(img.K.fx, sent[i].K.fx, 1e-3 * sent[i].K.fx);  // float on the wire
    EXPECT_NEAR(img.K.fy, sent[i].K.fy, 1e-3 * sent[i].K.fy);
    EXPECT_DOUBLE_EQ(img.K.cx, (img.K.width - 1) / 2.0);
    EXPECT_DOUBLE_EQ(img.K.cy, (img.K.height - 1) / 2.0);
    EXPECT_EQ(got[i].device_timestamp_us, sent[i].utime - sent[0].utime);
    // Wall-clock utime keeps the device's spacing exactly.
    EXPECT_EQ(got[i].utime - got[0].utime, sent[i].utime - sent[0].utime);
  }
}

int openni_devices() {
  if (openni::OpenNI::initialize() != openni::STATUS_OK) return -1;
  openni::Array<openni::DeviceInfo> list;
  openni::OpenNI::enumerateDevices(&list);
  const int n = list.getSize();
  openni::OpenNI::shutdown();
  return n;
}

}  // namespace

TEST(OpenNI2Driver, NoDeviceIsOneLineAndNonZeroExit) {
  const int devices = openni_devices();
  ASSERT_GE(devices, 0) << "OpenNI2 failed to initialise";
  if (devices > 0) GTEST_SKIP() << "a real OpenNI2 device is connected";
  const RunResult r = run({"--lcm-url", "memq://"}, 20);
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(count_lines(r.output), 1) << r.output;
  EXPECT_NE(r.output.find("no OpenNI2 device found"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("first device"), std::string::npos) << r.output;

  const RunResult u = run({"--lcm-url", "memq://", "--uri", "1d27/0601@9/9"}, 20);
  EXPECT_EQ(u.code, 1);
  EXPECT_EQ(count_lines(u.output), 1) << u.output;
  EXPECT_NE(u.output.find("device 1d27/0601@9/9"), std::string::npos) << u.output;

  const RunResult f = run({"--lcm-url", "memq://", "--oni", "/nonexistent/x.oni"}, 20);
  EXPECT_EQ(f.code, 1);
  EXPECT_EQ(count_lines(f.output), 1) << f.output;
  EXPECT_NE(f.output.find("recording /nonexistent/x.oni: no such file"), std::string::npos) << f.output;
}

TEST(OpenNI2Driver, OniToLogFramesUnchanged) {
  const auto frames = source_frames(640, 480, 24);
  const std::string oni = write_oni(frames, "log.oni"), log = temp_path("out.lcmlog");
  const RunResult r = run({"--lcm-url", "memq://", "--oni", oni, "--fast", "--log", log, "--no-publish", "--zlib", "1"});
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_FALSE(std::filesystem::exists(log + ".partial"));
  LogReader reader(log);
  LogEvent ev;
  std::vector<depth_frame_t> got;
  while (reader.next(ev)) {
    ASSERT_EQ(ev.channel, "STAIRS_DEPTH");
    depth_frame_t m;
    std::string error;
    ASSERT_TRUE(decode_message(ev.data.data(), ev.data.size(), m, error)) << error;
    EXPECT_EQ(m.encoding, +depth_frame_t::ENCODING_ZLIB_U16LE);
    EXPECT_EQ(ev.timestamp_us, m.utime);
    got.push_back(m);
  }
  expect_same_frames(got, frames);
  std::remove(oni.c_str());
  std::remove(log.c_str());
}

struct Subscriber {
  std::vector<depth_frame_t> frames;
  std::vector<daemon_status_t> status;
  int invalid = 0;
  void on_depth(const lcm::ReceiveBuffer* rb, const std::string&) {
    depth_frame_t m;
    std::string error;
    if (decode_message(rb->data, rb->data_size, m, error)) frames.push_back(m);
    else ++invalid;
  }
  void on_status(const lcm::ReceiveBuffer* rb, const std::string&, const daemon_status_t* s) {
    (void)rb;
    if (s->name == "stairs-openni2") status.push_back(*s);
  }
};

TEST(OpenNI2Driver, OniOverUdpmFramesUnchanged) {
  const std::string url = "udpm://239.255.76.67:7689?ttl=0&recv_buf_size=4194304";
  if (!stairs::test::ensure_multicast_loopback(url)) GTEST_SKIP() << stairs::test::kMulticastSkipReason;
  // Recorded speed (30 Hz) and raw 320x240: a paced stream that the driver
  // never has to drop from; --fast would burst frames faster than a loaded
  // receiver drains its UDP buffer, which loses datagrams, not driver frames.
  const auto frames = source_frames(320, 240, 30);
  const std::string oni = write_oni(frames, "udpm.oni"), out = temp_path("udpm.txt");
  lcm::LCM lcm(url);
  ASSERT_TRUE(lcm.good());
  Subscriber sub;
  lcm.subscribe("STAIRS_DEPTH_OPENNI2_TEST", &Subscriber::on_depth, &sub);
  const pid_t pid =
      spawn({"--lcm-url", url, "--oni", oni, "--zlib", "0", "--depth-channel", "STAIRS_DEPTH_OPENNI2_TEST"}, out);
  ASSERT_GT(pid, 0);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (sub.frames.size() < frames.size() && std::chrono::steady_clock::now() < deadline) lcm.handleTimeout(50);
  EXPECT_EQ(stairs::test::wait_exit(pid, 10), 0) << slurp(out);
  EXPECT_EQ(sub.invalid, 0);
  expect_same_frames(sub.frames, frames);
  std::remove(oni.c_str());
  std::remove(out.c_str());
}

TEST(OpenNI2Driver, LoopingPlaybackReportsStatusAndStopsCleanlyOnSigterm) {
  const std::string url = "udpm://239.255.76.67:7689?ttl=0&recv_buf_size=4194304";
  if (!stairs::test::ensure_multicast_loopback(url)) GTEST_SKIP() << stairs::test::kMulticastSkipReason;
  const auto frames = source_frames(160, 120, 10);
  const std::string oni = write_oni(frames, "loop.oni"), log = temp_path("loop.lcmlog"), out = temp_path("loop.txt");
  lcm::LCM lcm(url);
  ASSERT_TRUE(lcm.good());
  Subscriber sub;
  lcm.subscribe("STAIRS_STATUS_OPENNI2_TEST", &Subscriber::on_status, &sub);
  const pid_t pid = spawn({"--lcm-url", url, "--oni", oni, "--loop", "--log", log, "--depth-channel",
                           "STAIRS_DEPTH_OPENNI2_TEST2", "--status-channel", "STAIRS_STATUS_OPENNI2_TEST"},
                          out);
  ASSERT_GT(pid, 0);
  // Recorded speed (30 Hz) with 10 frames: 2.5 s is two loops and more.
  const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(2500);
  while (std::chrono::steady_clock::now() < until) lcm.handleTimeout(50);
  EXPECT_TRUE(std::filesystem::exists(log + ".partial"));
  EXPECT_FALSE(std::filesystem::exists(log));
  kill(pid, SIGTERM);
  EXPECT_EQ(stairs::test::wait_exit(pid, 10), 0) << slurp(out);
  ASSERT_FALSE(sub.status.empty()) << "no daemon_status_t in 2.5 s";
  EXPECT_GT(sub.status.back().published, 10) << "looping did not go past the end";
  EXPECT_GT(sub.status.back().rate_hz, 10.0f);
  EXPECT_FALSE(std::filesystem::exists(log + ".partial"));
  ASSERT_TRUE(std::filesystem::exists(log));
  LogReader reader(log);
  LogEvent ev;
  int n = 0;
  while (reader.next(ev)) {
    depth_frame_t m;
    DepthImage img;
    std::string error;
    ASSERT_TRUE(decode_message(ev.data.data(), ev.data.size(), m, error) && from_lcm(m, img, error)) << error;
    // Which recorded frame this is: its device timestamp (frames at i * 33333 us).
    const int64_t i = m.device_timestamp_us / 33'333;
    ASSERT_TRUE(i >= 0 && i < static_cast<int64_t>(frames.size()) && m.device_timestamp_us % 33'333 == 0)
        << "event " << n << " device timestamp " << m.device_timestamp_us;
    EXPECT_TRUE(img.depth == frames[i].depth) << "event " << n;
    ++n;
  }
  EXPECT_GT(n, 10);
  std::remove(oni.c_str());
  std::remove(log.c_str());
  std::remove(out.c_str());
}

// A real OpenNI2 stall: the recording has a 3 s hole between two frames, so
// the player delivers nothing for 2 s (its sanity cap). With a 500 ms frame
// timeout the driver must say the source is lost, reopen it and go on.
TEST(OpenNI2Driver, StalledSourceIsReportedAndReopened) {
  auto frames = source_frames(160, 120, 6);
  for (size_t i = 3; i < frames.size(); ++i) frames[i].utime += 3'000'000;
  const std::string oni = write_oni(frames, "stall.oni"), log = temp_path("stall.lcmlog");
  const RunResult r = run({"--lcm-url", "memq://", "--oni", oni, "--loop", "--timeout-ms", "500", "--max-frames",
                           "8", "--log", log, "--no-publish"},
                          40);
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("no depth frame from recording " + oni + " for 500 ms"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("reconnected to recording " + oni), std::string::npos) << r.output;
  LogReader reader(log);
  LogEvent ev;
  int n = 0;
  while (reader.next(ev)) ++n;
  EXPECT_EQ(n, 8);
  std::remove(oni.c_str());
  std::remove(log.c_str());
}

#ifdef STAIRS_HAVE_PERCEPTION
// The chain driver -> perception over udpm: perception's observations refer
// to frames the driver published (source_seq, source_utime).
TEST(OpenNI2Driver, OniThroughPerception) {
  const std::string url = "udpm://239.255.76.67:7690?ttl=0&recv_buf_size=4194304";
  if (!stairs::test::ensure_multicast_loopback(url)) GTEST_SKIP() << stairs::test::kMulticastSkipReason;
  const auto frames = source_frames(640, 480, 60);
  const std::string oni = write_oni(frames, "chain.oni"), out = temp_path("chain.txt"),
                    perception_out = temp_path("perception.txt");
  lcm::LCM lcm(url);
  ASSERT_TRUE(lcm.good());
  Subscriber depth;
  lcm.subscribe("STAIRS_DEPTH", &Subscriber::on_depth, &depth);
  struct Observations {
    std::vector<stair_observation_t> obs;
    int invalid = 0;
    void on(const lcm::ReceiveBuffer* rb, const std::string&) {
      stair_observation_t m;
      std::string error;
      if (decode_message(rb->data, rb->data_size, m, error)) obs.push_back(m);
      else ++invalid;
    }
  } observations;
  lcm.subscribe("STAIRS_OBSERVATION", &Observations::on, &observations);

  const std::string perception = std::string(STAIRS_BINARY_DIR) + "/bin/stairs-perception";
  std::vector<std::string> pargs = {perception, "--lcm-url", url};
  std::vector<char*> pargv;
  for (auto& a : pargs) pargv.push_back(a.data());
  pargv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, perception_out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  pid_t ppid = -1;
  ASSERT_EQ(posix_spawn(&ppid, perception.c_str(), &fa, nullptr, pargv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&fa);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));

  const pid_t pid = spawn({"--lcm-url", url, "--oni", oni}, out);  // recorded speed, 30 Hz
  ASSERT_GT(pid, 0);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  int exit_code = -2;
  while (std::chrono::steady_clock::now() < deadline) {
    lcm.handleTimeout(50);
    int status = 0;
    if (exit_code == -2 && waitpid(pid, &status, WNOHANG) == pid) {
      exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
      break;
    }
  }
  // Perception may still be working on the last frames.
  const auto drain = std::chrono::steady_clock::now() + std::chrono::seconds(3);
  while (std::chrono::steady_clock::now() < drain) lcm.handleTimeout(50);
  kill(ppid, SIGTERM);
  EXPECT_EQ(stairs::test::wait_exit(ppid, 10), 0) << slurp(perception_out);
  if (exit_code == -2) exit_code = stairs::test::wait_exit(pid, 5);
  EXPECT_EQ(exit_code, 0) << slurp(out);

  EXPECT_EQ(observations.invalid, 0);
  ASSERT_GE(observations.obs.size(), 5u) << slurp(perception_out);
  std::map<int32_t, int64_t> utime_of_seq;
  for (const auto& f : depth.frames) utime_of_seq[f.seq] = f.utime;
  for (const auto& o : observations.obs) {
    Observation obs;
    std::string error;
    EXPECT_TRUE(from_lcm(o, obs, error)) << error;
    ASSERT_TRUE(utime_of_seq.count(o.source_seq)) << "observation of a frame never published: " << o.source_seq;
    EXPECT_EQ(o.source_utime, utime_of_seq[o.source_seq]);
  }
  std::remove(oni.c_str());
  std::remove(out.c_str());
  std::remove(perception_out.c_str());
}
#endif
