// stairs-tracker as a real subprocess over UDP multicast on loopback:
// observations in, one model out per observation, a garbage message counted
// as invalid, the daemon survives it and stops cleanly on SIGTERM; given a
// config with a mount, its models carry the robot's base.
#include "tests/support/multicast.hpp"
#include "common/lcm_bridge.hpp"
#include "drivers/sim/synthetic_observations.hpp"

#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

using namespace stairs;

namespace {

const std::string kUrl = "udpm://239.255.76.67:7689?ttl=0&recv_buf_size=4194304";

struct Received {
  int models = 0, bad_models = 0, max_fused = 0, steps = 0, camera_valid = 0, base_valid = 0;
  double min_base_offset_m = 1e9, max_base_offset_m = 0.0;  // |camera - base| on the models with a base
  int64_t invalid = 0, dropped = 0;
  void on_model(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    stair_model_t msg;
    StairModel m;
    std::string error;
    if (!decode_message(rbuf->data, rbuf->data_size, msg, error) || !from_lcm(msg, m, error)) {
      ++bad_models;
      return;
    }
    ++models;
    max_fused = std::max(max_fused, m.observations_fused);
    camera_valid += m.camera_valid;
    if (m.base_valid) {
      ++base_valid;
      const double d = (m.camera_position_m - m.base_position_m).norm();
      min_base_offset_m = std::min(min_base_offset_m, d);
      max_base_offset_m = std::max(max_base_offset_m, d);
    }
    steps = 0;
    for (const auto& f : m.flights) steps += static_cast<int>(f.steps.size());
  }
  void on_status(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    daemon_status_t s;
    std::string error;
    if (decode_message(rbuf->data, rbuf->data_size, s, error) && s.name == "stairs-tracker") {
      invalid = s.invalid;
      dropped = s.dropped;
    }
  }
};

void pump(lcm::LCM& lcm, int ms) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(ms);
  while (std::chrono::steady_clock::now() < end) lcm.handleTimeout(20);
}

// Runs the daemon with `extra` options on a synthetic ascent of `n` observations (a garbage message
// after the 21st) and returns what it published; the daemon must survive and stop cleanly. Its
// channels end in `tag`: tests that ctest runs at once share the multicast group, not the channels.
Received run_tracker(const std::string& tag, const std::vector<std::string>& extra, int n) {
  Received rx;
  const std::string exe = std::string(STAIRS_BINARY_DIR) + "/bin/stairs-tracker";
  const std::string obs_channel = "TRK_TEST_OBS_" + tag, model_channel = "TRK_TEST_MODEL_" + tag,
                    status_channel = "TRK_TEST_STATUS_" + tag;
  std::vector<std::string> args = {exe, "--lcm-url", kUrl, "--observation-channel", obs_channel,
                                   "--model-channel", model_channel, "--status-channel", status_channel,
                                   "--reset-after-s", "3"};
  args.insert(args.end(), extra.begin(), extra.end());
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = fork();
  EXPECT_GE(pid, 0);
  if (pid < 0) return rx;
  if (pid == 0) {
    execv(exe.c_str(), argv.data());
    _exit(127);
  }
  lcm::LCM lcm(kUrl);
  EXPECT_TRUE(lcm.good());
  lcm.subscribe(model_channel, &Received::on_model, &rx);
  lcm.subscribe(status_channel, &Received::on_status, &rx);
  pump(lcm, 500);  // the daemon subscribes

  const auto g = synthetic::make_stair(9, 0.17, 0.28, 1.5);
  synthetic::ObservationMaker maker(g, 11, 256);
  const auto cams = synthetic::walk(g, true, 0.6, 30.0);
  for (int k = 0; k < n; ++k) {
    const stair_observation_t msg = to_lcm(maker.make(cams[k], k * 33333), k * 33333 + 1000);
    lcm.publish(obs_channel, &msg);
    if (k == 20) {
      const std::string garbage = "not an observation at all";
      lcm.publish(obs_channel, garbage.data(), static_cast<unsigned>(garbage.size()));
    }
    pump(lcm, 15);
  }
  pump(lcm, 1500);  // the last models and a status message arrive
  EXPECT_EQ(waitpid(pid, nullptr, WNOHANG), 0) << "the daemon died";

  kill(pid, SIGTERM);
  int status = 0;
  EXPECT_EQ(waitpid(pid, &status, 0), pid);
  EXPECT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  return rx;
}

}  // namespace

TEST(TrackerDaemon, ObservationsInModelsOutGarbageCounted) {
  if (!stairs::test::ensure_multicast_loopback(kUrl)) GTEST_SKIP() << stairs::test::kMulticastSkipReason;
  const int n = 60;
  const Received rx = run_tracker("PLAIN", {}, n);
  EXPECT_EQ(rx.models, n);
  EXPECT_EQ(rx.bad_models, 0);
  EXPECT_GT(rx.max_fused, n / 2);
  EXPECT_GE(rx.steps, 4);
  EXPECT_EQ(rx.invalid, 1);
  EXPECT_GT(rx.camera_valid, n / 2);
  EXPECT_EQ(rx.base_valid, 0) << "no mount, no base";
}

// Issue 15: with the robot's mount in its config (config/stairs-sim-robot.json) every model with a
// camera carries the robot's base, 0.45 m from the camera along the base's z axis.
TEST(TrackerDaemon, AMountInTheConfigGivesTheRobotsBase) {
  if (!stairs::test::ensure_multicast_loopback(kUrl)) GTEST_SKIP() << stairs::test::kMulticastSkipReason;
  const int n = 60;
  const Received rx =
      run_tracker("MOUNT", {"--config", std::string(STAIRS_SOURCE_DIR) + "/config/stairs-sim-robot.json"}, n);
  EXPECT_EQ(rx.models, n);
  EXPECT_EQ(rx.bad_models, 0);
  EXPECT_GT(rx.camera_valid, n / 2);
  EXPECT_EQ(rx.base_valid, rx.camera_valid);
  EXPECT_NEAR(rx.min_base_offset_m, 0.45, 1e-5);
  EXPECT_NEAR(rx.max_base_offset_m, 0.45, 1e-5);
}
