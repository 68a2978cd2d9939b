// Real LCM transport: a publisher and a subscriber in two processes over UDP
// multicast on loopback, and in one process over memq.
#include "tests/support/multicast.hpp"
#include "common/lcm_bridge.hpp"

#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <random>
#include <set>

using namespace stairs;

namespace {

DepthImage frame(int seq) {
  DepthImage img;
  img.K = {640, 480, 525, 525, 319.5, 239.5};
  img.depth.resize(640 * 480);
  std::mt19937 rng(seq);
  for (auto& d : img.depth) d = static_cast<uint16_t>(600 + rng() % 3000);
  img.seq = seq;
  img.utime = seq;
  return img;
}

struct Collector {
  std::set<int> seqs;
  int invalid = 0;
  void on_frame(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    depth_frame_t m;
    DepthImage img;
    std::string error;
    if (decode_message(rbuf->data, rbuf->data_size, m, error) && from_lcm(m, img, error) &&
        img.depth == frame(img.seq).depth)
      seqs.insert(img.seq);
    else
      ++invalid;
  }
};

}  // namespace

TEST(Transport, UdpMulticastTwoProcesses) {
  // A test-only port keeps other LCM traffic on this machine out of the count.
  const std::string url = "udpm://239.255.76.67:7687?ttl=0&recv_buf_size=4194304";
  if (!test::ensure_multicast_loopback(url)) GTEST_SKIP() << test::kMulticastSkipReason;
  lcm::LCM sub(url);
  ASSERT_TRUE(sub.good());
  Collector c;
  sub.subscribe("STAIRS_DEPTH_TEST", &Collector::on_frame, &c);
  const int n = 30;
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {  // publisher process: its own LCM instance
    lcm::LCM pub(url);
    if (!pub.good()) _exit(3);
    usleep(200000);
    for (int i = 0; i < n; ++i) {
      const depth_frame_t m = to_lcm(frame(i), 1);
      pub.publish("STAIRS_DEPTH_TEST", &m);
      usleep(33000);  // 30 Hz
    }
    _exit(0);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (static_cast<int>(c.seqs.size()) < n && std::chrono::steady_clock::now() < deadline) sub.handleTimeout(100);
  int status = 0;
  waitpid(pid, &status, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  EXPECT_EQ(c.invalid, 0);
  EXPECT_EQ(static_cast<int>(c.seqs.size()), n) << "full 640x480 frames lost over udpm";
}

TEST(Transport, MemqInProcess) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  Collector c;
  lcm.subscribe("STAIRS_DEPTH", &Collector::on_frame, &c);
  for (int i = 0; i < 5; ++i) {
    const depth_frame_t m = to_lcm(frame(i), i % 2);
    ASSERT_EQ(lcm.publish("STAIRS_DEPTH", &m), 0);
  }
  lcm.publish("STAIRS_DEPTH", "garbage", 7);
  for (int i = 0; i < 6; ++i) lcm.handleTimeout(100);
  EXPECT_EQ(c.seqs, (std::set<int>{0, 1, 2, 3, 4}));
  EXPECT_EQ(c.invalid, 1);
}
