// scripts/run-live as a user runs it: a log through lcm-logplayer, perception
// and the tracker as real processes, lcm-logger recording, all on one URL;
// then the recording scored as it ran. And Ctrl-C stops every program.
#include "tests/support/daemon_process.hpp"
#include "tests/support/multicast.hpp"
#include "tools/recorded.hpp"
#include "tools/replay.hpp"

#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <thread>

namespace stairs {
namespace {

const std::string kScript = std::string(STAIRS_SOURCE_DIR) + "/scripts/run-live";
const std::string kLog = std::string(STAIRS_SOURCE_DIR) + "/logs/up_handheld.lcmlog";

std::string url(int port) { return "udpm://239.255.76.67:" + std::to_string(port) + "?ttl=0&recv_buf_size=4194304"; }

// Runs the launcher with `args` (BUILD_DIR pointing at this build); its pid.
pid_t launch(const std::vector<std::string>& args) {
  const pid_t pid = fork();
  if (pid == 0) {
    setenv("BUILD_DIR", STAIRS_BINARY_DIR, 1);
    std::vector<char*> argv{const_cast<char*>(kScript.c_str())};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(kScript.c_str(), argv.data());
    _exit(127);
  }
  return pid;
}

// A program runs whose command line matches the regex `pattern`. Its first
// character goes in brackets so that the shell running pgrep, whose own command
// line holds the pattern, does not match it.
bool running_with(const std::string& pattern) {
  const std::string self_proof = "[" + pattern.substr(0, 1) + "]" + pattern.substr(1);
  return std::system(("pgrep -f '" + self_proof + "' >/dev/null").c_str()) == 0;
}

TEST(RunLive, ALogThroughTheLiveChainGivesAnObservationAndAModelForEveryFrame) {
  const std::string u = url(7681);
  if (!test::ensure_multicast_loopback(u)) GTEST_SKIP() << test::kMulticastSkipReason;
  const std::string rec = std::string(STAIRS_BINARY_DIR) + "/run_live_test.lcmlog";
  std::filesystem::remove(rec);
  ASSERT_EQ(test::wait_exit(launch({"--log", kLog, "--lcm-url", u, "--record", rec}), 60.0), 0);

  const eval::RunResult live = eval::score_recorded(rec, eval::RecordedOptions{});
  const eval::RunResult offline = eval::replay(kLog, eval::ReplayOptions{});
  ASSERT_TRUE(live.recorded && live.score && offline.score);
  // Frames in = observations out = models out, nothing lost.
  EXPECT_EQ(live.frames_processed, offline.frames_processed);
  EXPECT_EQ(live.recorded->observations, live.frames_processed);
  EXPECT_EQ(live.recorded->models, live.frames_processed);
  EXPECT_EQ(live.recorded->frames_without_observation, 0);
  EXPECT_EQ(live.recorded->rejected_messages, 0);
  // Perception is per frame: over the wire it finds what it finds offline.
  EXPECT_EQ(live.score->frame_steps_matched, offline.score->frame_steps_matched);
  EXPECT_EQ(live.score->model_steps_detected, offline.score->model_steps_detected);
  EXPECT_GT(live.score->model_steps_detected, 0);
  std::filesystem::remove(rec);
}

TEST(RunLive, CtrlCStopsEveryProgramOfTheChain) {
  const std::string u = url(7683);
  if (!test::ensure_multicast_loopback(u)) GTEST_SKIP() << test::kMulticastSkipReason;
  const pid_t pid = launch({"--sim", "straight_up", "--lcm-url", u});
  std::this_thread::sleep_for(std::chrono::milliseconds(2000));
  const std::string group = "239.255.76.67:7683";  // in the command line of every program of this chain
  EXPECT_TRUE(running_with("stairs-perception.*" + group)) << "the chain did not start";
  kill(pid, SIGINT);
  EXPECT_EQ(test::wait_exit(pid, 10.0), 130);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  for (const char* p : {"stairs-perception", "stairs-tracker", "stairs-sim"})
    EXPECT_FALSE(running_with(std::string(p) + ".*" + group)) << p << " still runs";
}

TEST(RunLive, AMissingLogIsOneLineNamingIt) {
  EXPECT_EQ(test::wait_exit(launch({"--log", "/nonexistent/run.lcmlog"}), 10.0), 1);
}

}  // namespace
}  // namespace stairs
