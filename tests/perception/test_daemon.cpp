// stairs-perception as a real subprocess over LCM UDP multicast on loopback:
// frames in, observations out; a garbage message is counted as invalid and
// the daemon keeps going; SIGTERM gives a clean exit.
#include "common/lcm_bridge.hpp"
#include "synthetic.hpp"

#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <thread>

namespace stairs {
namespace {

const char* kUrl = "udpm://239.255.76.67:7693?ttl=0";

struct Sink {
  std::vector<Observation> observations;
  daemon_status_t last_status{};
  bool have_status = false;
  void on_obs(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    stair_observation_t msg;
    Observation obs;
    std::string error;
    if (decode_message(rbuf->data, rbuf->data_size, msg, error) && from_lcm(msg, obs, error))
      observations.push_back(obs);
  }
  void on_status(const lcm::ReceiveBuffer*, const std::string&, const daemon_status_t* s) {
    if (s->name != "stairs-perception") return;
    last_status = *s;
    have_status = true;
  }
};

TEST(PerceptionDaemon, SubprocessOverUdpm) {
  const std::string exe = std::string(STAIRS_BINARY_DIR) + "/bin/stairs-perception";
  ASSERT_EQ(access(exe.c_str(), X_OK), 0) << exe;
  lcm::LCM lcm(kUrl);
  ASSERT_TRUE(lcm.good());
  Sink sink;
  lcm.subscribe("PERC_TEST_OBS", &Sink::on_obs, &sink);
  lcm.subscribe("PERC_TEST_STATUS", &Sink::on_status, &sink);

  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    execl(exe.c_str(), exe.c_str(), "--lcm-url", kUrl, "--depth-channel", "PERC_TEST_DEPTH", "--observation-channel",
          "PERC_TEST_OBS", "--status-channel", "PERC_TEST_STATUS", static_cast<char*>(nullptr));
    _exit(127);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // subscription in place

  const char garbage[] = "not a depth frame";
  lcm.publish("PERC_TEST_DEPTH", garbage, sizeof(garbage));
  DepthImage img = test::render_stairs(320, 240, -35, 0, 1.0, 4, 1.2);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  for (int i = 0; std::chrono::steady_clock::now() < deadline; ++i) {
    if (i < 20) {
      img.seq = i;
      img.utime = 1000 + i;
      const depth_frame_t msg = to_lcm(img, 1);
      lcm.publish("PERC_TEST_DEPTH", &msg);
    }
    lcm.handleTimeout(100);
    if (sink.observations.size() >= 3 && sink.have_status && sink.last_status.invalid >= 1) break;
  }
  kill(pid, SIGTERM);
  int wstatus = 0;
  ASSERT_EQ(waitpid(pid, &wstatus, 0), pid);
  EXPECT_TRUE(WIFEXITED(wstatus));
  EXPECT_EQ(WEXITSTATUS(wstatus), 0);

  ASSERT_GE(sink.observations.size(), 3u);
  for (const Observation& o : sink.observations) {
    EXPECT_TRUE(o.camera.valid);
    EXPECT_EQ(o.direction, Direction::Up);
    EXPECT_GE(o.steps.size(), 3u);
    EXPECT_GE(o.source_utime, 1000);
  }
  ASSERT_TRUE(sink.have_status);
  EXPECT_EQ(sink.last_status.invalid, 1);  // the garbage, and it kept going
  EXPECT_GE(sink.last_status.published, 3);
}

}  // namespace
}  // namespace stairs
